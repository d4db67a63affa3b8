// The C ABI's structs with the C layout: blittable, sequential, the C field names, C arrays
// as fixed buffers. ffi/tests/csharp.rs compares every size, field, offset and type with the
// header compiled by the C compiler. Start a struct from its maker (Default(), Sphere(),
// Box()): it sets struct_size, which the library checks.
using System;
using System.Runtime.InteropServices;

namespace Springwater
{
    /// <summary>Three floats: a point or a vector in the water's local space (y up).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Float3
    {
        public float x, y, z;

        public Float3(float x, float y, float z)
        {
            this.x = x;
            this.y = y;
            this.z = z;
        }

        public override string ToString()
        {
            return "(" + x + ", " + y + ", " + z + ")";
        }

        internal static unsafe Float3 Read(float* p)
        {
            return new Float3(p[0], p[1], p[2]);
        }

        internal unsafe void Write(float* p)
        {
            p[0] = x;
            p[1] = y;
            p[2] = z;
        }
    }

    /// <summary>
    /// A rotation as a unit quaternion (x, y, z, w), body to world: a floating body's
    /// orientation. <see cref="Identity"/> is upright.
    /// </summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Rotation
    {
        public float x, y, z, w;

        public Rotation(float x, float y, float z, float w)
        {
            this.x = x;
            this.y = y;
            this.z = z;
            this.w = w;
        }

        /// <summary>No rotation: (0, 0, 0, 1).</summary>
        public static Rotation Identity
        {
            get { return new Rotation(0, 0, 0, 1); }
        }

        /// <summary>A turn of <paramref name="radians"/> about the unit axis (ax, ay, az).</summary>
        public static Rotation AboutAxis(float ax, float ay, float az, float radians)
        {
            float s = (float)Math.Sin(0.5 * radians);
            return new Rotation(ax * s, ay * s, az * s, (float)Math.Cos(0.5 * radians));
        }

        /// <summary>The vector v turned by this rotation.</summary>
        public Float3 Rotate(Float3 v)
        {
            // v + 2w (q × v) + 2 q × (q × v), with q the vector part.
            float tx = 2 * (y * v.z - z * v.y), ty = 2 * (z * v.x - x * v.z), tz = 2 * (x * v.y - y * v.x);
            return new Float3(
                v.x + w * tx + (y * tz - z * ty),
                v.y + w * ty + (z * tx - x * tz),
                v.z + w * tz + (x * ty - y * tx));
        }

        /// <summary>The angle in degrees between the body's up axis and the world's (its heel).</summary>
        public float HeelDegrees
        {
            get
            {
                double up = Math.Max(-1.0, Math.Min(1.0, 1.0 - 2.0 * (x * x + z * z)));
                return (float)(Math.Acos(up) * 180.0 / Math.PI);
            }
        }

        public override string ToString()
        {
            return "(" + x + ", " + y + ", " + z + ", " + w + ")";
        }

        internal static unsafe Rotation Read(float* p)
        {
            return new Rotation(p[0], p[1], p[2], p[3]);
        }

        internal unsafe void Write(float* p)
        {
            p[0] = x;
            p[1] = y;
            p[2] = z;
            p[3] = w;
        }
    }

    /// <summary>The model's parameters (seed defaults from <see cref="Default"/>).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SwParams
    {
        /// <summary>sizeof(SwParams), set by <see cref="Default"/>: keep it.</summary>
        public uint struct_size;
        /// <summary>Nodes per row (at least 2).</summary>
        public uint cols;
        /// <summary>Rows of nodes (at least 2).</summary>
        public uint rows;
        /// <summary>Rest distance between neighbouring nodes, world units.</summary>
        public float spacing;
        /// <summary>Mass of each node.</summary>
        public float mass;
        /// <summary>Spring coefficient c.</summary>
        public float stiffness;
        /// <summary>Viscosity (damping per unit of velocity).</summary>
        public float viscosity;
        /// <summary>Timestep of one step, model time (below the critical timestep).</summary>
        public float dt;
        /// <summary>Rest length over initial length of every spring.</summary>
        public float rest_ratio;
        /// <summary>Model time per second of the caller's clock.</summary>
        public float time_scale;
        /// <summary>Uniform acceleration on free nodes, world units per second².</summary>
        public float acceleration_x;
        public float acceleration_y;
        public float acceleration_z;
        /// <summary>Native.SW_BOUNDARY_PINNED, _FREE or _ABSORBING.</summary>
        public int boundary;
        /// <summary>Rings of damping of an absorbing boundary (32 by default).</summary>
        public uint absorbing_width;

        /// <summary>The seed's defaults on a 128 × 128 grid.</summary>
        public static SwParams Default()
        {
            return Native.sw_params_default();
        }

        /// <summary>The guaranteed (large-wave) stability limit of these parameters: dt must stay under it.</summary>
        public unsafe float CriticalDt()
        {
            float dt;
            SwParams p = this;
            SpringwaterException.Check(Native.sw_params_critical_dt(&p, &dt));
            return dt;
        }

        /// <summary>The linear stability limit at rest of these parameters.</summary>
        public unsafe float LinearDtLimit()
        {
            float dt;
            SwParams p = this;
            SpringwaterException.Check(Native.sw_params_linear_dt_limit(&p, &dt));
            return dt;
        }

        /// <summary>How fast ripples travel on a surface of these parameters, world units per second.</summary>
        public unsafe float RippleSpeed()
        {
            float speed;
            SwParams p = this;
            SpringwaterException.Check(Native.sw_params_ripple_speed(&p, &speed));
            return speed;
        }

        /// <summary>Sets time_scale so that ripples travel <paramref name="speed"/> world units per second; the other fields stay.</summary>
        public unsafe void SetRippleSpeed(float speed)
        {
            SwParams p = this;
            SpringwaterException.Check(Native.sw_params_set_ripple_speed(&p, speed));
            this = p;
        }
    }

    /// <summary>The LOD index buffer's parameters (<see cref="Default"/>).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SwLodParams
    {
        public uint struct_size;
        /// <summary>Patch size in cells, a power of two from 1 to 4096.</summary>
        public uint patch_cells;
        /// <summary>Number of levels, 1 to log2(patch_cells) + 1.</summary>
        public uint levels;
        /// <summary>Distance within which patches get full detail, world units.</summary>
        public float first_range;
        /// <summary>Relative distance past a range boundary before a patch changes level.</summary>
        public float hysteresis;

        public static SwLodParams Default()
        {
            return Native.sw_lod_params_default();
        }

        /// <summary>The most levels patch_cells allows, log2(patch_cells) + 1 (the other fields but levels are checked).</summary>
        public unsafe uint MaxLevels()
        {
            uint max;
            SwLodParams p = this;
            SpringwaterException.Check(Native.sw_lod_params_max_levels(&p, &max));
            return max;
        }
    }

    /// <summary>The eye and the bottom for the refraction coordinates (<see cref="Default"/>, then set the eye).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SwRefraction
    {
        public uint struct_size;
        /// <summary>The eye in the water's local space.</summary>
        public float eye_x;
        public float eye_y;
        public float eye_z;
        /// <summary>Depth of the flat bottom below the rest surface (at least 0).</summary>
        public float depth;
        /// <summary>Index of refraction of the water (1 to 10; water 1.333).</summary>
        public float ior;

        public static SwRefraction Default()
        {
            return Native.sw_refraction_default();
        }

        /// <summary>Schlick's reflectance at normal incidence, ((ior − 1) / (ior + 1))²: a shader's Fresnel R0.</summary>
        public unsafe float R0()
        {
            float r0;
            SwRefraction p = this;
            SpringwaterException.Check(Native.sw_refraction_r0(&p, &r0));
            return r0;
        }
    }

    /// <summary>
    /// The procedural boat's dimensions and resolution (<see cref="Default"/>, then change
    /// fields): <see cref="Hull.Boat"/> makes its hull. The bow points to +x, y is up, the
    /// origin is on the keel amidships.
    /// </summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SwBoatShape
    {
        public uint struct_size;
        /// <summary>Length overall, transom to stem, world units (default 6).</summary>
        public float length;
        /// <summary>Greatest beam, world units (default 2).</summary>
        public float beam;
        /// <summary>Depth from the keel to the deck amidships, world units (default 1).</summary>
        public float depth;
        /// <summary>Cross-sections from the transom to the stem (2 to 1024; default 40).</summary>
        public uint stations;
        /// <summary>Edges per side of each cross-section (2 to 1024; default 12).</summary>
        public uint segments;

        public static SwBoatShape Default()
        {
            return Native.sw_boat_shape_default();
        }
    }

    /// <summary>The water at one point: height, unit normal, velocity (per second).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public unsafe struct SwSample
    {
        public float height;
        public fixed float normal[3];
        public fixed float velocity[3];

        public Float3 Normal
        {
            get { fixed (float* p = normal) return Float3.Read(p); }
        }

        public Float3 Velocity
        {
            get { fixed (float* p = velocity) return Float3.Read(p); }
        }
    }

    /// <summary>
    /// One node's packed vertex, 32 bytes: position (Float32 × 3 at byte 0), normal
    /// (Float32 × 3 at 12), refracted bottom texture coordinate (Float32 × 2 at 24).
    /// </summary>
    [StructLayout(LayoutKind.Sequential)]
    public unsafe struct SwVertex
    {
        public fixed float position[3];
        public fixed float normal[3];
        public fixed float uv[2];

        public Float3 Position
        {
            get { fixed (float* p = position) return Float3.Read(p); }
        }

        public Float3 Normal
        {
            get { fixed (float* p = normal) return Float3.Read(p); }
        }
    }

    /// <summary>Kinetic and spring potential energy (a diagnostic).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SwEnergy
    {
        public double kinetic;
        public double potential;
        public double total;
    }

    /// <summary>
    /// A floating body, a rigid body, plain data: make it with <see cref="Sphere"/>,
    /// <see cref="Box"/> or <see cref="Hull.Floater"/>, add it with
    /// <see cref="WaterSurface.AddFloater"/> (<see cref="WaterSurface.AddHullFloater"/>),
    /// read it back with <see cref="WaterSurface.Floater"/>, or keep it in your own engine
    /// and ask <see cref="WaterSurface.BodyForces"/>. Velocities and forces are per second.
    /// </summary>
    [StructLayout(LayoutKind.Sequential)]
    public unsafe struct SwFloater
    {
        public uint struct_size;
        /// <summary>Native.SW_SHAPE_SPHERE, SW_SHAPE_BOX or SW_SHAPE_HULL.</summary>
        public int shape;
        /// <summary>The sphere's radius (0 for a box).</summary>
        public float radius;
        /// <summary>The box's half size along x, y, z (0 for a sphere).</summary>
        public fixed float half_extents[3];
        public float mass;
        /// <summary>Drag rate, per second.</summary>
        public float drag;
        public fixed float position[3];
        public fixed float velocity[3];
        /// <summary>External force for the next step only.</summary>
        public fixed float push[3];
        /// <summary>Read only: the water's force on the body during its last step.</summary>
        public fixed float water_force[3];
        /// <summary>Orientation, body to world, a unit quaternion (x, y, z, w).</summary>
        public fixed float orientation[4];
        /// <summary>Angular velocity, radians per second about the world's axes.</summary>
        public fixed float angular_velocity[3];
        /// <summary>External torque about the centre of mass for the next step only.</summary>
        public fixed float push_torque[3];
        /// <summary>Read only: the water's torque on the body during its last step.</summary>
        public fixed float water_torque[3];
        /// <summary>1: inertia is the body's; 0: the shape's at uniform density.</summary>
        public int has_inertia;
        /// <summary>Inertia tensor in the body's axes, column by column; read back, the one in use.</summary>
        public fixed float inertia[9];

        /// <summary>A sphere at rest centred at (x, y, z) with the default drag.</summary>
        public static SwFloater Sphere(float radius, float mass, float x, float y, float z)
        {
            return Native.sw_floater_sphere(radius, mass, x, y, z);
        }

        /// <summary>A box of half extents (hx, hy, hz) at rest centred at (x, y, z).</summary>
        public static SwFloater Box(float hx, float hy, float hz, float mass, float x, float y, float z)
        {
            return Native.sw_floater_box(hx, hy, hz, mass, x, y, z);
        }

        /// <summary>
        /// The world velocity of the body's point at world (x, y, z), per second: Velocity +
        /// AngularVelocity × (point − Position), for a body of any shape.
        /// </summary>
        public Float3 VelocityAt(float x, float y, float z)
        {
            var v = new Float3();
            SwFloater f = this;
            SpringwaterException.Check(Native.sw_floater_velocity_at(&f, x, y, z, &v.x));
            return v;
        }

        /// <summary>
        /// The distance from a sphere's or a box's centre to its farthest point (a hull's is
        /// <see cref="Hull.BoundingRadius"/>); the body is checked as AddFloater checks it.
        /// </summary>
        public float BoundingRadius()
        {
            float r;
            SwFloater f = this;
            SpringwaterException.Check(Native.sw_floater_bounding_radius(&f, &r));
            return r;
        }

        public Float3 HalfExtents
        {
            get { fixed (float* p = half_extents) return Float3.Read(p); }
            set { fixed (float* p = half_extents) value.Write(p); }
        }

        public Float3 Position
        {
            get { fixed (float* p = position) return Float3.Read(p); }
            set { fixed (float* p = position) value.Write(p); }
        }

        public Float3 Velocity
        {
            get { fixed (float* p = velocity) return Float3.Read(p); }
            set { fixed (float* p = velocity) value.Write(p); }
        }

        public Float3 Push
        {
            get { fixed (float* p = push) return Float3.Read(p); }
            set { fixed (float* p = push) value.Write(p); }
        }

        public Float3 WaterForce
        {
            get { fixed (float* p = water_force) return Float3.Read(p); }
        }

        public Rotation Orientation
        {
            get { fixed (float* p = orientation) return Rotation.Read(p); }
            set { fixed (float* p = orientation) value.Write(p); }
        }

        public Float3 AngularVelocity
        {
            get { fixed (float* p = angular_velocity) return Float3.Read(p); }
            set { fixed (float* p = angular_velocity) value.Write(p); }
        }

        public Float3 PushTorque
        {
            get { fixed (float* p = push_torque) return Float3.Read(p); }
            set { fixed (float* p = push_torque) value.Write(p); }
        }

        public Float3 WaterTorque
        {
            get { fixed (float* p = water_torque) return Float3.Read(p); }
        }

        /// <summary>Inertia tensor entry (row, col) in the body's axes.</summary>
        public float Inertia(int row, int col)
        {
            if (row < 0 || row > 2 || col < 0 || col > 2)
                throw new ArgumentOutOfRangeException("row or col", "0 to 2");
            fixed (float* p = inertia) return p[3 * col + row];
        }

        /// <summary>Sets the body's own inertia tensor (body axes, symmetric; has_inertia = 1).</summary>
        public void SetInertia(float xx, float yy, float zz, float xy, float yz, float zx)
        {
            has_inertia = 1;
            fixed (float* p = inertia)
            {
                p[0] = xx; p[1] = xy; p[2] = zx;
                p[3] = xy; p[4] = yy; p[5] = yz;
                p[6] = zx; p[7] = yz; p[8] = zz;
            }
        }
    }

    /// <summary>
    /// The water's push on a body over one tick (<see cref="WaterSurface.BodyForces"/>):
    /// world frame, the torque about the body's centre of mass.
    /// </summary>
    [StructLayout(LayoutKind.Sequential)]
    public unsafe struct SwBodyForces
    {
        public uint struct_size;
        public fixed float force[3];
        public fixed float torque[3];

        public static SwBodyForces Default()
        {
            return Native.sw_body_forces_default();
        }

        /// <summary>Buoyancy and drag through the centre of mass (gravity is the engine's).</summary>
        public Float3 Force
        {
            get { fixed (float* p = force) return Float3.Read(p); }
        }

        /// <summary>The torque about the centre of mass, world axes.</summary>
        public Float3 Torque
        {
            get { fixed (float* p = torque) return Float3.Read(p); }
        }
    }

    /// <summary>Gravity (per second²) and water density for the floating bodies.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SwBuoyancy
    {
        public uint struct_size;
        public float gravity;
        public float density;

        public static SwBuoyancy Default()
        {
            return Native.sw_buoyancy_default();
        }
    }

    /// <summary>
    /// A host's job system (Box2D's enqueueTask / finishTask): function pointers made with
    /// Marshal.GetFunctionPointerForDelegate (kept alive by the caller; under IL2CPP, static
    /// methods marked MonoPInvokeCallback), set with Native.sw_surface_set_job_system.
    /// </summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SwJobSystem
    {
        public uint struct_size;
        public uint worker_count;
        /// <summary>SwEnqueueTaskFn.</summary>
        public IntPtr enqueue_task;
        /// <summary>SwFinishTaskFn.</summary>
        public IntPtr finish_task;
        public IntPtr user_context;

        public static SwJobSystem Default()
        {
            return Native.sw_job_system_default();
        }
    }
}
