// The C# layer's tests, a console runner for Mono (no NUnit): `mono runner.exe OUT_DIR`.
// Prints `ok NAME` or `FAIL NAME: ...` per test, `refused NAME STATUS MESSAGE` per refusal,
// and `value KEY HEX` lines that ffi/tests/csharp.rs recomputes through the Rust API; writes
// OUT_DIR/frame_loop.txt (the bits of every node's x, y, z) for the comparison with the
// command line's CSV. Exit code 1 if any test failed.
using System;
using System.Collections.Generic;
using System.IO;
using System.Runtime.CompilerServices;
using System.Text;
using System.Threading;
using Springwater;

static unsafe partial class Runner
{
    static int failures;

    static void Main(string[] args)
    {
        string outDir = args[0];
        Run("frame_loop_writes_what_the_command_line_computes", () => FrameLoop(outDir));
        Run("the_frame_loop_allocates_nothing", NoAllocation);
        Run("every_refusal_throws_the_library_message_and_changes_nothing", Refusals);
        Run("dispose_twice_is_harmless_and_use_after_dispose_is_refused", DisposeTwice);
        Run("the_finalizer_destroys_forgotten_surfaces", Finalizer);
        Run("floating_bodies", Floaters);
        Run("the_moving_window", Window);
        Run("snapshots_round_trip_and_state_hashes_follow_the_state", Snapshots);
        Run("two_threads_each_owning_a_surface_get_the_same_bits", TwoThreads);
        Run("queries_agree_with_the_buffers", Queries);
        Run("a_heeled_box_rights_itself", RigidBodies);
        Run("the_lattice_node_by_node", Lattice);
        Run("frames_forces_velocities_and_the_lod_mesh", Frames);
        Run("the_hulls_the_library_makes_and_points_on_bodies", Shapes);
        Run("rain_and_wakes", Disturbances);
        Console.WriteLine(failures == 0 ? "all passed" : failures + " failed");
        Environment.Exit(failures == 0 ? 0 : 1);
    }

    static void Run(string name, Action test)
    {
        try
        {
            test();
            Console.WriteLine("ok " + name);
        }
        catch (Exception e)
        {
            failures++;
            Console.WriteLine("FAIL " + name + ": " + e);
        }
    }

    static void Assert(bool condition, string what)
    {
        if (!condition)
            throw new Exception("assertion failed: " + what);
    }

    static void Value(string key, string value)
    {
        Console.WriteLine("value " + key + " " + value);
    }

    static string Hex(float f)
    {
        return BitConverter.ToUInt32(BitConverter.GetBytes(f), 0).ToString("x8");
    }

    static ulong Fnv(float[] values, int count)
    {
        ulong h = 0xcbf29ce484222325;
        for (int i = 0; i < count; i++)
            foreach (byte b in BitConverter.GetBytes(values[i]))
                h = (h ^ b) * 0x100000001b3;
        return h;
    }

    static ulong Positions(WaterSurface w)
    {
        var xyz = new float[3 * w.NodeCount];
        w.WritePositions(xyz);
        return Fnv(xyz, xyz.Length);
    }

    // ---- The frame loop against the command line ----

    /// The command line's `simulate --size 48x40 --steps 90 --drop 20,15,1,3`, as a game
    /// runs it: 60 frames per second, each frame reading the vertex buffer, the LOD indices
    /// and a few heights.
    static void FrameLoop(string outDir)
    {
        using (var water = new WaterSurface(48, 40))
        {
            Assert(water.Cols == 48 && water.Rows == 40 && water.NodeCount == 48 * 40, "the size");
            water.DropAt(20, 15, 1, 3);
            var frame = new Frame(water);
            uint steps = 0;
            while (steps < 90)
                steps += frame.Run(1f / 60f);
            Assert(steps == 90, "90 steps, one frame at a time (took " + steps + ")");
            // The clock, read back: 90 steps of dt 0.4 at the default time scale of 24 are
            // 36 units of model time, 1.5 s; less than a step owed, nothing dropped.
            Assert(water.Steps == 90, "Steps reads 90");
            Assert(Math.Abs(water.ModelTime - 36) < 1e-5 && Math.Abs(water.Time - 1.5) < 1e-6,
                "ModelTime " + water.ModelTime + " and Time " + water.Time);
            Assert(water.OwedSeconds >= 0 && water.OwedSeconds < 1.0 / 60 && water.DroppedSeconds == 0,
                "owed " + water.OwedSeconds + ", dropped " + water.DroppedSeconds);
            Assert(water.CriticalDt > 0.4f && water.CriticalDt < 1, "CriticalDt " + water.CriticalDt);
            uint capSteps;
            bool carry;
            water.SetStepCap(7, true);
            water.GetStepCap(out capSteps, out carry);
            Assert(capSteps == 7 && carry, "GetStepCap reads what SetStepCap set");
            var xyz = new float[3 * water.NodeCount];
            water.WritePositions(xyz);
            var lines = new StringBuilder();
            for (int i = 0; i < water.NodeCount; i++)
                lines.Append(Hex(xyz[3 * i])).Append(' ').Append(Hex(xyz[3 * i + 1]))
                    .Append(' ').Append(Hex(xyz[3 * i + 2])).Append('\n');
            File.WriteAllText(Path.Combine(outDir, "frame_loop.txt"), lines.ToString());
            // The packed vertex buffer's positions are the same bits.
            for (int i = 0; i < water.NodeCount; i++)
            {
                Float3 p = frame.Vertices[i].Position;
                Assert(p.x == xyz[3 * i] && p.y == xyz[3 * i + 1] && p.z == xyz[3 * i + 2],
                    "vertex " + i + "'s position is the positions buffer's");
            }
            Assert(frame.Indices > 0 && frame.Indices % 3 == 0, "LOD triangles");
        }
    }

    /// What a game does each frame, in buffers made once.
    sealed class Frame
    {
        readonly WaterSurface water;
        public readonly SwVertex[] Vertices;
        public uint[] IndexBuffer = new uint[0];
        public int Indices;
        readonly float[] points = { 10.5f, 12.25f, 30, 20 };
        readonly SwSample[] samples = new SwSample[2];
        SwRefraction view = SwRefraction.Default();
        public float Height;

        public Frame(WaterSurface water)
        {
            this.water = water;
            Vertices = new SwVertex[water.NodeCount];
            view.eye_x = 24;
            view.eye_y = 30;
            view.eye_z = -20;
            var lod = SwLodParams.Default();
            lod.patch_cells = 8;
            lod.levels = 3;
            lod.first_range = 12;
            water.SetLodParams(lod);
        }

        public uint Run(float seconds)
        {
            uint steps = water.Advance(seconds);
            water.WriteVertices(view, Vertices);
            if (water.UpdateLod(view.eye_x, view.eye_y, view.eye_z))
            {
                Indices = water.LodIndexCount;
                if (IndexBuffer.Length < Indices)
                    IndexBuffer = new uint[Indices];
                water.WriteLodIndices(IndexBuffer);
            }
            water.Sample(points, samples);
            Height = water.HeightAt(20.5f, 15.25f);
            return steps;
        }
    }

    static void NoAllocation()
    {
        using (var water = new WaterSurface(64, 64))
        {
            water.DropAt(32, 32, 1, 3);
            water.AddFloater(SwFloater.Sphere(1.5f, 6, 20, 0, 20));
            var frame = new Frame(water);
            var normals = new float[3 * water.NodeCount];
            var uvs = new float[2 * water.NodeCount];
            var found = new byte[2];
            var xz = new float[] { 1, 1, -5, 3 };
            var each = new SwSample[2];
            var ids = new ulong[4];
            var snapshot = new byte[water.SnapshotSize + 1024];
            for (int i = 0; i < 5; i++)
                frame.Run(1f / 60f);
            water.StateHash();
            long before = GC.GetAllocatedBytesForCurrentThread();
            for (int i = 0; i < 100; i++)
            {
                frame.Run(1f / 60f);
                water.AddForceAt(10, 10, 0, -1, 0);
                water.WriteNormals(normals);
                water.WriteRefractionUvs(SwRefraction.Default(), uvs);
                water.WriteVertices(SwRefraction.Default(), new Span<SwVertex>(frame.Vertices));
                water.SampleEach(xz, each, found);
                water.NormalAt(5, 5);
                water.VelocityAt(5, 5);
                water.FloaterIds(ids);
                SwFloater body = water.Floater(ids[0]);
                water.PushFloater(ids[0], 0, 1, 0);
                water.SaveInto(snapshot);
                water.StateHash();
                float x, z;
                water.Origin(out x, out z);
                Assert(water.Interpolation < 1, "the interpolation");
                Assert(body.mass == 6, "the body");
            }
            long after = GC.GetAllocatedBytesForCurrentThread();
            Assert(after == before, (after - before) + " bytes allocated in 100 frames");
            Assert(found[0] == 1 && found[1] == 0, "SampleEach found the point on the water only");
        }
    }

    // ---- Refusals ----

    /// The thread's last error read straight from the C ABI, independently of the layer.
    static string LibraryMessage()
    {
        var buf = new byte[4096];
        UIntPtr n;
        fixed (byte* p = buf)
            n = Native.sw_last_error(p, (UIntPtr)buf.Length);
        return Encoding.UTF8.GetString(buf, 0, (int)n - 1);
    }

    static void Refused(string name, int status, string fragment, Action call)
    {
        try
        {
            call();
        }
        catch (SpringwaterException e)
        {
            Console.WriteLine("refused " + name + " " + e.StatusName + " " + e.Message);
            Assert(e.Status == status, name + ": status " + e.StatusName);
            Assert(e.Message.IndexOf(fragment, StringComparison.OrdinalIgnoreCase) >= 0,
                name + ": the message names " + fragment + ": " + e.Message);
            if (!name.StartsWith("csharp_"))
                Assert(e.Message == LibraryMessage(), name + ": the message is the library's");
            return;
        }
        throw new Exception(name + " was not refused");
    }

    static void Refusals()
    {
        const int Arg = Native.SW_ERROR_INVALID_ARGUMENT, Small = Native.SW_ERROR_BUFFER_TOO_SMALL,
            Outside = Native.SW_ERROR_OUTSIDE_GRID, Null = Native.SW_ERROR_NULL_POINTER;
        Refused("one_column", Arg, "at least 2x2", () => new WaterSurface(1, 8));
        Refused("negative_size", Arg, "too large", () => new WaterSurface(-3, 8));
        var p = SwParams.Default();
        p.dt = 0.6f;
        Refused("past_the_critical_timestep", Arg, "critical", () => new WaterSurface(p));
        p = SwParams.Default();
        p.struct_size = 0;
        Refused("params_without_struct_size", Arg, "struct_size", () => new WaterSurface(p));
        Refused("load_garbage", Native.SW_ERROR_SNAPSHOT, "magic", () => WaterSurface.Load(new byte[40]));
        Refused("load_empty", Native.SW_ERROR_SNAPSHOT, "truncated", () => WaterSurface.Load(null));

        using (var w = new WaterSurface(24, 20))
        {
            w.DropAt(10, 10, 0.5f, 2);
            w.Advance(0.1f);
            ulong id = w.AddFloater(SwFloater.Sphere(1, 2, 8, 0, 8));
            ulong state = w.StateHash();
            int n = w.NodeCount;
            Refused("advance_nan", Arg, "NaN", () => w.Advance(float.NaN));
            Refused("advance_negative", Arg, "= -1", () => w.Advance(-1));
            Refused("drop_nan", Arg, "NaN", () => w.DropAt(float.NaN, 3, 1, 1));
            Refused("drop_radius_zero", Arg, "radius = 0", () => w.DropAt(3, 3, 1, 0));
            Refused("force_infinite", Arg, "force = inf", () => w.AddForceAt(3, 3, 0, float.PositiveInfinity, 0));
            Refused("height_outside", Outside, "x -5", () => w.HeightAt(-5, 3));
            Refused("normal_outside", Outside, "z 40", () => w.NormalAt(3, 40));
            Refused("velocity_outside", Outside, "x 100", () => w.VelocityAt(100, 3));
            Refused("sample_outside", Outside, "x -1", () => w.Sample(new float[] { 1, 1, -1, 2 }, new SwSample[2]));
            Refused("sample_results_short", Small, "out holds 1, the call needs 2", () => w.Sample(new float[] { 1, 1, 2, 2 }, new SwSample[1]));
            Refused("csharp_sample_odd_xz", Arg, "pair", () => w.Sample(new float[] { 1, 1, 2 }, new SwSample[2]));
            Refused("sample_each_found_short", Small, "found holds 1", () => w.SampleEach(new float[] { 1, 1, 2, 2 }, new SwSample[2], new byte[1]));
            Refused("positions_short", Small, "needs " + 3 * n, () => w.WritePositions(new float[3 * n - 1]));
            Refused("positions_null", Small, "holds 0", () => w.WritePositions((float[])null));
            Refused("normals_short", Small, "needs " + 3 * n, () => w.WriteNormals(new float[n]));
            Refused("uvs_short", Small, "needs " + 2 * n, () => w.WriteRefractionUvs(SwRefraction.Default(), new float[2 * n - 2]));
            var view = SwRefraction.Default();
            view.ior = 0.5f;
            Refused("refraction_ior", Arg, "ior", () => w.WriteRefractionUvs(view, new float[2 * n]));
            Refused("vertices_short", Small, "needs " + n, () => w.WriteVertices(SwRefraction.Default(), new SwVertex[n - 1]));
            Refused("refraction_without_struct_size", Arg, "struct_size", () => w.WriteVertices(new SwRefraction(), new SwVertex[n]));
            var lod = SwLodParams.Default();
            lod.patch_cells = 3;
            Refused("lod_patch_cells", Arg, "patch_cells", () => w.SetLodParams(lod));
            Refused("lod_eye_nan", Arg, "NaN", () => w.UpdateLod(float.NaN, 1, 1));
            w.UpdateLod(12, 20, 10);
            Refused("lod_indices_short", Small, "needs " + w.LodIndexCount, () => w.WriteLodIndices(new uint[w.LodIndexCount - 1]));
            Refused("lod_indices_empty", Small, "needs " + w.LodIndexCount, () => w.WriteLodIndices(new uint[0]));
            Refused("step_cap_zero", Arg, "max steps per frame = 0", () => w.SetStepCap(0, false));
            Refused("simd_level_unknown", Arg, "level 99", () => w.SetSimdLevel(99));
            Refused("shift_too_far", Arg, "15,728,640", () => w.Shift(20000000, 0));
            Refused("follow_nan", Arg, "NaN", () => { int a, b; w.Follow(float.NaN, 1, out a, out b); });
            Refused("rebase_too_far", Arg, "15,728,640", () => w.Rebase(long.MaxValue / 2, 0));
            Refused("save_short", Small, "needs " + w.SnapshotSize, () => w.SaveInto(new byte[10]));
            byte[] snapshot = w.Save();
            var damaged = (byte[])snapshot.Clone();
            damaged[damaged.Length / 2] ^= 1;
            Refused("restore_damaged", Native.SW_ERROR_SNAPSHOT, "checksum", () => w.Restore(damaged));
            Refused("restore_truncated", Native.SW_ERROR_SNAPSHOT, "truncated", () => w.Restore(snapshot, snapshot.Length - 4));
            Refused("csharp_restore_length", Arg, "length", () => w.Restore(snapshot, snapshot.Length + 1));
            Refused("floater_radius", Arg, "radius = -1", () => w.AddFloater(SwFloater.Sphere(-1, 1, 3, 0, 3)));
            Refused("floater_without_struct_size", Arg, "struct_size", () => w.AddFloater(new SwFloater()));
            Refused("floater_unknown", Native.SW_ERROR_NO_SUCH_FLOATER, "floater 99", () => w.Floater(99));
            Refused("set_floater_unknown", Native.SW_ERROR_NO_SUCH_FLOATER, "floater 99", () => w.SetFloater(99, SwFloater.Sphere(1, 1, 3, 0, 3)));
            Refused("push_nan", Arg, "NaN", () => w.PushFloater(id, float.NaN, 0, 0));
            Refused("floater_ids_short", Small, "ids holds 0, the call needs 1", () => w.FloaterIds(new ulong[0]));
            var buoyancy = w.Buoyancy;
            buoyancy.gravity = -1;
            Refused("buoyancy_negative", Arg, "gravity = -1", () => w.Buoyancy = buoyancy);
            Refused("torque_nan", Arg, "NaN", () => w.PushFloaterTorque(id, 0, float.NaN, 0));
            Refused("pin_past_the_last_node", Arg, "node", () => w.SetPinned(n, true));
            Refused("csharp_negative_node", Arg, "node -1", () => w.SetMass(-1, 4));
            Refused("mass_negative", Arg, "mass = -1", () => w.SetMass(3, -1));
            Refused("masses_short", Small, "masses holds 1", () => w.SetMasses(new float[1]));
            var heavy = new float[n];
            for (int i = 0; i < n; i++)
                heavy[i] = 4;
            heavy[n - 1] = 0.01f;
            Refused("masses_one_too_light", Arg, "critical", () => w.SetMasses(heavy));
            Refused("viscosity_nan", Arg, "NaN", () => w.SetViscosity(3, float.NaN));
            Refused("pinned_short", Small, "needs " + n, () => w.WritePinned(new byte[n - 1]));
            Refused("spring_off_the_grid", Arg, "no spring", () => { float r, c; w.Spring(Native.SW_FAMILY_E, 23, out r, out c); });
            Refused("spring_family_unknown", Arg, "family is 4", () => w.SetSpring(4, 3, 1, 7));
            Refused("raw_null_out", Null, "NULL", () =>
                SpringwaterException.Check(Native.sw_surface_height_at(w.RawHandle, 1, 1, null)));
            Assert(w.StateHash() == state, "the refused calls changed nothing");
            w.RemoveFloater(id);
            Refused("remove_twice", Native.SW_ERROR_NO_SUCH_FLOATER, "floater " + id, () => w.RemoveFloater(id));
        }
        using (var w = new WaterSurface(16, 16))
        {
            w.DropAt(8, 8, 1e30f, 2);
            Refused("step_non_finite", Native.SW_ERROR_NON_FINITE, "non-finite", () => w.Step(5));
        }
    }

    // ---- Lifetime ----

    static void DisposeTwice()
    {
        var w = new WaterSurface(8, 8);
        IntPtr raw = w.RawHandle;
        Assert(!w.IsDisposed, "live");
        w.Dispose();
        w.Dispose();
        Assert(w.IsDisposed, "disposed");
        Refused("after_dispose_advance", Native.SW_ERROR_INVALID_HANDLE, "not a live surface", () => w.Advance(0.1f));
        Refused("after_dispose_positions", Native.SW_ERROR_INVALID_HANDLE, "not a live surface", () => w.WritePositions(new float[192]));
        Refused("after_dispose_hash", Native.SW_ERROR_INVALID_HANDLE, "not a live surface", () => w.StateHash());
        UIntPtr n;
        Assert(Native.sw_surface_node_count(raw, &n) == Native.SW_ERROR_INVALID_HANDLE, "the native surface is gone");
    }

    static void Finalizer()
    {
        var handles = new List<IntPtr>();
        // Surfaces made and dropped on a thread that then ends: nothing on any stack keeps
        // them (Mono scans stacks conservatively).
        var t = new Thread(() =>
        {
            for (int i = 0; i < 20; i++)
                handles.Add(new WaterSurface(8, 8).RawHandle);
        });
        t.Start();
        t.Join();
        UIntPtr n;
        for (int round = 0; round < 10 && Live(handles) > 0; round++)
        {
            GC.Collect();
            GC.WaitForPendingFinalizers();
        }
        Assert(Live(handles) == 0, Live(handles) + " of 20 forgotten surfaces are still alive");
        Assert(Native.sw_surface_node_count(handles[0], &n) == Native.SW_ERROR_INVALID_HANDLE, "gone");
    }

    static int Live(List<IntPtr> handles)
    {
        int live = 0;
        UIntPtr n;
        foreach (IntPtr h in handles)
            if (Native.sw_surface_node_count(h, &n) == Native.SW_OK)
                live++;
        return live;
    }

    // ---- Floating bodies, window, snapshots ----

    static float[] FloaterFloats(SwFloater f)
    {
        return new[] {
            f.radius, f.HalfExtents.x, f.HalfExtents.y, f.HalfExtents.z, f.mass, f.drag,
            f.Position.x, f.Position.y, f.Position.z, f.Velocity.x, f.Velocity.y, f.Velocity.z,
            f.Push.x, f.Push.y, f.Push.z, f.WaterForce.x, f.WaterForce.y, f.WaterForce.z,
            f.Orientation.x, f.Orientation.y, f.Orientation.z, f.Orientation.w,
            f.AngularVelocity.x, f.AngularVelocity.y, f.AngularVelocity.z,
            f.PushTorque.x, f.PushTorque.y, f.PushTorque.z,
            f.WaterTorque.x, f.WaterTorque.y, f.WaterTorque.z };
    }

    /// Kept in step with `floaters()` in ffi/tests/csharp.rs, which runs it through Rust;
    /// a body's floats in the order of `floater_floats` in ffi/tests/common/mod.rs.
    static void Floaters()
    {
        var p = SwParams.Default();
        p.cols = 40;
        p.rows = 32;
        p.boundary = Native.SW_BOUNDARY_ABSORBING;
        p.absorbing_width = 5;
        using (var w = new WaterSurface(p))
        {
            var b = w.Buoyancy;
            Assert(b.gravity == SwBuoyancy.Default().gravity, "the default buoyancy");
            b.density = 1.2f;
            w.Buoyancy = b;
            var ball = SwFloater.Sphere(1.5f, 5, 14, 0.5f, 12);
            ball.Velocity = new Float3(0.6f, 0, 0.3f);
            ulong a = w.AddFloater(ball);
            ulong box = w.AddFloater(SwFloater.Box(2, 0.75f, 1, 8, 26, 0, 18));
            Assert(a == 0 && box == 1 && w.FloaterCount == 2, "ids from 0, in order");
            var ids = new ulong[3];
            Assert(w.FloaterIds(ids) == 2 && ids[0] == a && ids[1] == box, "the ids");
            w.DropAt(20, 16, 0.6f, 2.5f);
            for (int frame = 0; frame < 50; frame++)
            {
                if (frame == 20)
                    w.PushFloater(a, 50, 0, -20);
                w.Advance(1f / 60f);
            }
            var moved = w.Floater(box);
            moved.Position = new Float3(24, moved.Position.y, 18);
            moved.drag = 12;
            w.SetFloater(box, moved);
            w.Step(30);
            var floats = new List<float>();
            floats.AddRange(FloaterFloats(w.Floater(a)));
            floats.AddRange(FloaterFloats(w.Floater(box)));
            Value("floaters", Fnv(floats.ToArray(), floats.Count).ToString("x16"));
            Value("floaters_water", Positions(w).ToString("x16"));
            Value("floaters_hash", w.StateHash().ToString("x16"));
            // They float: the ball's centre stays within a radius of the calm surface.
            Assert(Math.Abs(w.Floater(a).Position.y) < 1.5f, "the ball floats");
            Assert(w.Floater(a).WaterForce.y > 0, "the water pushes the ball up");
        }
    }

    /// Kept in step with `window()` in ffi/tests/csharp.rs.
    static void Window()
    {
        var p = SwParams.Default();
        p.cols = 40;
        p.rows = 32;
        p.boundary = Native.SW_BOUNDARY_FREE;
        using (var w = new WaterSurface(p))
        {
            w.DropAt(18, 14, 0.8f, 3);
            for (int frame = 0; frame < 20; frame++)
                w.Advance(1f / 60f);
            int cols = w.Cols, rows = w.Rows;
            var before = new float[3 * cols * rows];
            w.WritePositions(before);
            w.Shift(5, -3);
            var after = new float[before.Length];
            w.WritePositions(after);
            for (int row = 0; row < rows; row++)
                for (int col = 0; col < cols; col++)
                {
                    int i = 3 * (row * cols + col), c = col + 5, r = row - 3;
                    if (c < cols && r >= 0)
                    {
                        int j = 3 * (r * cols + c);
                        Assert(after[i] == before[j] && after[i + 1] == before[j + 1] && after[i + 2] == before[j + 2],
                            "node " + col + "," + row + " is the water that was at " + c + "," + r);
                    }
                    else
                        Assert(after[i + 1] == 0, "the strip that came in is calm");
                }
            float ox, oz;
            w.Origin(out ox, out oz);
            Assert(ox == 5 && oz == -3, "the origin moved by the shift");
            long oc, orow;
            w.OriginCells(out oc, out orow);
            Assert(oc == 5 && orow == -3, "OriginCells counts the shift's cells");
            Assert(w.FollowDeadZone >= 1 && w.FollowDeadZone == (uint)Math.Max(1, Math.Min(cols, rows) / 8),
                "FollowDeadZone " + w.FollowDeadZone);
            int dc, dr;
            Assert(!w.Follow(ox + 20, oz + 16, out dc, out dr) && dc == 0 && dr == 0, "the centre is in the dead zone");
            Assert(w.Follow(ox + 33, oz + 5, out dc, out dr), "a point near the edge moves the window");
            Value("follow", dc + " " + dr);
            for (int frame = 0; frame < 10; frame++)
                w.Advance(1f / 60f);
            w.Rebase(2, 1);
            w.Origin(out ox, out oz);
            Value("origin", Hex(ox) + " " + Hex(oz));
            Value("window_height", Hex(w.HeightAt(ox + 15.5f, oz + 12.25f)));
            Value("window", Positions(w).ToString("x16"));
            Value("window_hash", w.StateHash().ToString("x16"));
        }
    }

    static void Snapshots()
    {
        using (var w = new WaterSurface(32, 24))
        using (var twin = new WaterSurface(32, 24))
        {
            w.DropAt(12, 10, 0.7f, 2);
            w.AddFloater(SwFloater.Sphere(1, 3, 16, 0, 12));
            Assert(w.StateHash() != twin.StateHash(), "different states, different hashes");
            for (int frame = 0; frame < 20; frame++)
                w.Advance(1f / 60f);
            byte[] snapshot = w.Save();
            var reused = new byte[snapshot.Length + 100];
            Assert(w.SaveInto(reused) == snapshot.Length, "SaveInto's size");
            for (int i = 0; i < snapshot.Length; i++)
                Assert(reused[i] == snapshot[i], "SaveInto writes Save's bytes");
            ulong hashAt20 = w.StateHash();
            for (int frame = 0; frame < 30; frame++)
                w.Advance(1f / 60f);
            ulong end = Positions(w), endHash = w.StateHash();
            Assert(endHash != hashAt20, "the hash follows the state");

            using (var loaded = WaterSurface.Load(snapshot))
            {
                Assert(loaded.StateHash() == hashAt20 && loaded.FloaterCount == 1, "a loaded snapshot is the saved state");
                for (int frame = 0; frame < 30; frame++)
                    loaded.Advance(1f / 60f);
                Assert(Positions(loaded) == end && loaded.StateHash() == endHash, "loaded, it continues bit for bit");
            }
            twin.Restore(reused, snapshot.Length);
            Assert(twin.StateHash() == hashAt20, "restored");
            for (int frame = 0; frame < 30; frame++)
                twin.Advance(1f / 60f);
            Assert(Positions(twin) == end && twin.StateHash() == endHash, "restored, it continues bit for bit");
            w.Restore(snapshot);
            Assert(w.StateHash() == hashAt20, "rolled back");
        }
    }

    static ulong ThreadRun()
    {
        using (var w = new WaterSurface(64, 48))
        {
            w.DropAt(20, 20, 1, 3);
            w.AddFloater(SwFloater.Sphere(2, 8, 40, 0, 24));
            var frame = new Frame(w);
            for (int i = 0; i < 120; i++)
            {
                if (i % 40 == 0)
                    w.DropAt(10 + i / 4, 30, -0.5f, 2);
                frame.Run(1f / 60f);
            }
            return Positions(w) ^ w.StateHash();
        }
    }

    static void TwoThreads()
    {
        ulong alone = ThreadRun();
        var results = new ulong[2];
        var threads = new Thread[2];
        for (int k = 0; k < 2; k++)
        {
            int slot = k;
            threads[k] = new Thread(() => results[slot] = ThreadRun());
            threads[k].Start();
        }
        foreach (var t in threads)
            t.Join();
        Assert(results[0] == alone && results[1] == alone, "both threads computed the single thread's bits");
    }

    static void Queries()
    {
        using (var w = new WaterSurface(24, 24))
        {
            w.DropAt(12, 12, 0.5f, 3);
            w.Advance(0.25f);
            var xyz = new float[3 * w.NodeCount];
            var normals = new float[3 * w.NodeCount];
            w.WritePositions(xyz);
            w.WriteNormals(new Span<float>(normals));
            var samples = new SwSample[1];
            w.Sample(new float[] { 7, 9 }, samples);
            int node = 9 * 24 + 7;
            Assert(w.HeightAt(7, 9) == xyz[3 * node + 1], "the height at a node's rest place is its y");
            Assert(samples[0].height == w.HeightAt(7, 9), "Sample's height is HeightAt's");
            Float3 n = w.NormalAt(7, 9), v = w.VelocityAt(7, 9);
            Assert(samples[0].Normal.y == n.y && samples[0].Velocity.y == v.y, "Sample's normal and velocity");
            Assert(n.y > 0.5f && Math.Abs(n.x * n.x + n.y * n.y + n.z * n.z - 1) < 1e-4, "a unit normal, up");
            Assert(w.SetSimdLevel(Native.SW_SIMD_SCALAR) == Native.SW_SIMD_SCALAR, "every CPU runs scalar");
            Assert(WaterSurface.SimdLevelName(w.SimdLevel) == "scalar", "forced to scalar");
            int widest = WaterSurface.DetectSimdLevel();
            Assert(WaterSurface.SimdLevelAvailable(widest) && WaterSurface.SimdLevelAvailable(Native.SW_SIMD_SCALAR),
                "the detected level and scalar are available");
            Assert(!WaterSurface.SimdLevelAvailable(99), "an unknown level is not");
            Assert(w.SetSimdLevel(widest) == widest, "the detected level runs unclamped");
            var limits = SwParams.Default();
            float critical = limits.CriticalDt(), linear = limits.LinearDtLimit();
            Assert(critical > limits.dt && critical < 1 && linear >= critical,
                "the limits of the defaults: " + critical + ", " + linear);
            limits.mass = 0;
            Refused("params_critical_dt_mass", Native.SW_ERROR_INVALID_ARGUMENT, "mass", () => limits.CriticalDt());
            Assert(w.Contains(7, 9) && w.Contains(23, 23), "points on the water");
            Assert(!w.Contains(-0.5f, 3) && !w.Contains(3, float.NaN), "points off it");
            ulong calm = w.StateHash();
            w.AddForce(node, 0, 1, 0);
            Assert(w.StateHash() != calm, "a node's force is state until the step");
            w.ClearForces();
            Assert(w.StateHash() == calm, "ClearForces takes it back");
            w.AddVelocity(node, 0, 0.5f, 0);
            Assert(w.VelocityAt(7, 9).y > v.y, "AddVelocity moves the node up");
            Refused("add_force_nan", Native.SW_ERROR_INVALID_ARGUMENT, "NaN", () => w.AddForce(node, float.NaN, 0, 0));
            Assert(WaterSurface.Version.Length > 0 && w.Energy.total > 0, "version and energy");
        }
    }
}
