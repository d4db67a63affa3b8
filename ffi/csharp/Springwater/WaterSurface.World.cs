using System;

namespace Springwater
{
    // Floating bodies, the moving window, snapshots and the state hash.
    public sealed unsafe partial class WaterSurface
    {
        // ---- Floating bodies ----

        /// <summary>
        /// Adds a floating body (SwFloater.Sphere or SwFloater.Box; a hull body goes through
        /// AddHullFloater) and returns its id, never reused by this surface. It steps with
        /// the water, pitches and rolls, and is part of its snapshots.
        /// </summary>
        public ulong AddFloater(SwFloater body)
        {
            ulong id;
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_add_floater(s.Ptr, &body, &id));
            return id;
        }

        /// <summary>A floating body's current state.</summary>
        public SwFloater Floater(ulong id)
        {
            // Any maker sets struct_size, which the library checks before it fills the struct.
            SwFloater body = Native.sw_floater_sphere(1, 1, 0, 0, 0);
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_floater(s.Ptr, id, &body));
            return body;
        }

        /// <summary>Replaces a body's state (teleport, turn, velocities, mass, drag, inertia, shape); water_force and water_torque are kept.</summary>
        public void SetFloater(ulong id, SwFloater body)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_set_floater(s.Ptr, id, &body));
        }

        /// <summary>Adds a force (per second², times mass) to a body for the next step only.</summary>
        public void PushFloater(ulong id, float fx, float fy, float fz)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_push_floater(s.Ptr, id, fx, fy, fz));
        }

        /// <summary>
        /// Adds a body whose shape is <paramref name="hull"/> (start <paramref name="body"/>
        /// from hull.Floater) and returns its id. The surface keeps the mesh: the hull may be
        /// disposed afterwards. A hull body read back says Native.SW_SHAPE_HULL, and
        /// SetFloater with it keeps the body's mesh.
        /// </summary>
        public ulong AddHullFloater(Hull hull, SwFloater body)
        {
            if (hull == null)
                throw new ArgumentNullException("hull");
            ulong id;
            using (var h = hull.Enter())
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_add_hull_floater(s.Ptr, h.Ptr, &body, &id));
            return id;
        }

        /// <summary>
        /// Adds a force acting at the world point (x, y, z) to a body for the next step only:
        /// through its centre of mass, and the torque (point − position) × force.
        /// </summary>
        public void PushFloaterAt(ulong id, Float3 force, Float3 point)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_push_floater_at(
                    s.Ptr, id, force.x, force.y, force.z, point.x, point.y, point.z));
        }

        /// <summary>Adds a torque about a body's centre of mass (world axes) for the next step only.</summary>
        public void PushFloaterTorque(ulong id, float tx, float ty, float tz)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_push_floater_torque(s.Ptr, id, tx, ty, tz));
        }

        /// <summary>
        /// The water's force and torque on a sphere or box body your own engine owns, over
        /// its coming tick of <paramref name="seconds"/> (the engine's fixed step): apply both
        /// for the tick, with gravity, the same mass and the inertia body.Inertia reads back.
        /// The water gets the opposite (the body makes waves); call it once per tick.
        /// Allocates nothing.
        /// </summary>
        public SwBodyForces BodyForces(SwFloater body, float seconds)
        {
            SwBodyForces push = Native.sw_body_forces_default();
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_body_forces(s.Ptr, &body, seconds, &push));
            return push;
        }

        /// <summary>BodyForces for a body whose shape is <paramref name="hull"/>.</summary>
        public SwBodyForces BodyForces(Hull hull, SwFloater body, float seconds)
        {
            if (hull == null)
                throw new ArgumentNullException("hull");
            SwBodyForces push = Native.sw_body_forces_default();
            using (var h = hull.Enter())
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_hull_body_forces(
                    s.Ptr, h.Ptr, &body, seconds, &push));
            return push;
        }

        /// <summary>Removes a body; its id stays unused.</summary>
        public void RemoveFloater(ulong id)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_remove_floater(s.Ptr, id));
        }

        /// <summary>The number of floating bodies.</summary>
        public int FloaterCount
        {
            get
            {
                UIntPtr n;
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_floater_count(s.Ptr, &n));
                return checked((int)n.ToUInt64());
            }
        }

        /// <summary>
        /// Copies the bodies' ids, in the order they were added, and returns their number; a
        /// shorter array is refused (SW_ERROR_BUFFER_TOO_SMALL).
        /// </summary>
        public int FloaterIds(ulong[] ids)
        {
            UIntPtr count;
            ulong none;
            int length = ids == null ? 0 : ids.Length;
            fixed (ulong* p = ids)
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_floater_ids(
                    s.Ptr, length == 0 ? &none : p, (UIntPtr)length, &count));
            return checked((int)count.ToUInt64());
        }

        /// <summary>Gravity and water density for the bodies.</summary>
        public SwBuoyancy Buoyancy
        {
            get
            {
                SwBuoyancy b = Native.sw_buoyancy_default();
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_buoyancy(s.Ptr, &b));
                return b;
            }
            set
            {
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_set_buoyancy(s.Ptr, &value));
            }
        }

        // ---- The moving window ----

        /// <summary>
        /// Moves the window by whole cells: node (col, row) afterwards is the water that was at
        /// (col + dcols, row + drows), bit for bit; the strip that comes in is calm.
        /// </summary>
        public void Shift(int dcols, int drows)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_shift(s.Ptr, dcols, drows));
        }

        /// <summary>
        /// Shifts the window so that world (x, z) is back near its middle once it has left a
        /// dead zone; returns whether it moved, and the shift made.
        /// </summary>
        public bool Follow(float x, float z, out int dcols, out int drows)
        {
            int* shift = stackalloc int[2];
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_follow(s.Ptr, x, z, shift));
            dcols = shift[0];
            drows = shift[1];
            return dcols != 0 || drows != 0;
        }

        /// <summary>World (x, z) of node (0, 0)'s rest place.</summary>
        public void Origin(out float x, out float z)
        {
            float* origin = stackalloc float[2];
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_origin(s.Ptr, origin));
            x = origin[0];
            z = origin[1];
        }

        /// <summary>The whole cells the window has travelled since the surface was made.</summary>
        public void OriginCells(out long cols, out long rows)
        {
            long* cells = stackalloc long[2];
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_origin_cells(s.Ptr, cells));
            cols = cells[0];
            rows = cells[1];
        }

        /// <summary>Half the side of Follow's dead zone, in cells.</summary>
        public uint FollowDeadZone
        {
            get
            {
                uint cells;
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_follow_dead_zone(s.Ptr, &cells));
                return cells;
            }
        }

        /// <summary>A floating origin: moves the frame the surface speaks by whole cells.</summary>
        public void Rebase(long dcols, long drows)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_rebase(s.Ptr, dcols, drows));
        }

        // ---- Snapshots ----

        /// <summary>The size in bytes of a snapshot of the current state.</summary>
        public int SnapshotSize
        {
            get
            {
                UIntPtr size;
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_save(s.Ptr, null, UIntPtr.Zero, &size));
                return checked((int)size.ToUInt64());
            }
        }

        /// <summary>A snapshot of the whole state (a new array; SaveInto reuses one).</summary>
        public byte[] Save()
        {
            var bytes = new byte[SnapshotSize];
            SaveInto(bytes);
            return bytes;
        }

        /// <summary>
        /// Writes a snapshot into <paramref name="buffer"/> (longer is fine) and returns its
        /// size; a shorter buffer is refused (SW_ERROR_BUFFER_TOO_SMALL).
        /// </summary>
        public int SaveInto(byte[] buffer)
        {
            UIntPtr size;
            byte none;
            int length = buffer == null ? 0 : buffer.Length;
            fixed (byte* p = buffer)
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_save(
                    s.Ptr, length == 0 ? &none : p, (UIntPtr)length, &size));
            return checked((int)size.ToUInt64());
        }

        /// <summary>Replaces the state with a snapshot (its first <paramref name="length"/> bytes); a damaged one is refused.</summary>
        public void Restore(byte[] snapshot, int length)
        {
            if (snapshot != null && (length < 0 || length > snapshot.Length))
                throw new SpringwaterException(
                    Native.SW_ERROR_INVALID_ARGUMENT,
                    "length " + length + " is outside the snapshot's " + snapshot.Length + " bytes");
            fixed (byte* p = snapshot)
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_restore(s.Ptr, p, (UIntPtr)length));
        }

        /// <summary>Replaces the state with a snapshot; a damaged one is refused and nothing changes.</summary>
        public void Restore(byte[] snapshot)
        {
            Restore(snapshot, snapshot == null ? 0 : snapshot.Length);
        }

        // ---- The state hash ----

        /// <summary>
        /// A 64-bit hash of everything that decides the surface's future (the library's
        /// XXH3-64 state hash): equal states give equal hashes on every SIMD level, thread
        /// count and architecture; a rollback session compares them frame by frame. Allocates
        /// nothing.
        /// </summary>
        public ulong StateHash()
        {
            ulong hash;
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_state_hash(s.Ptr, &hash));
            return hash;
        }
    }
}
