using System;

namespace Springwater
{
    // The lattice node by node: pins, per-node masses and viscosities, single springs.
    // Nodes are row-major indices, row * Cols + col; the per-node arrays hold NodeCount
    // values (they may be longer). Masses and viscosities are the lattice's, like
    // SwParams.mass and SwParams.viscosity.
    public sealed unsafe partial class WaterSurface
    {
        // ---- Pins ----

        /// <summary>Pins or frees a node: a pinned node never moves (pinning zeroes its velocity).</summary>
        public void SetPinned(int node, bool pinned)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_set_pinned(s.Ptr, Node(node), pinned ? 1 : 0));
        }

        /// <summary>Whether a node is pinned.</summary>
        public bool IsPinned(int node)
        {
            int pinned;
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_is_pinned(s.Ptr, Node(node), &pinned));
            return pinned != 0;
        }

        /// <summary>Every node's pin, 1 pinned or 0 free.</summary>
        public void WritePinned(byte[] pinned)
        {
            using (var s = Enter())
            fixed (byte* p = pinned)
                SpringwaterException.Check(Native.sw_surface_write_pinned(s.Ptr, p, Size(Count(pinned))));
        }

        // ---- Masses and viscosities ----

        /// <summary>Sets a node's mass (> 0); refused if it would put dt past the critical timestep.</summary>
        public void SetMass(int node, float mass)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_set_mass(s.Ptr, Node(node), mass));
        }

        /// <summary>Sets every node's mass, all checked before any changes.</summary>
        public void SetMasses(float[] masses)
        {
            using (var s = Enter())
            fixed (float* p = masses)
                SpringwaterException.Check(Native.sw_surface_set_masses(s.Ptr, p, Size(Count(masses))));
        }

        /// <summary>Every node's mass.</summary>
        public void WriteMasses(float[] masses)
        {
            using (var s = Enter())
            fixed (float* p = masses)
                SpringwaterException.Check(Native.sw_surface_write_masses(s.Ptr, p, Size(Count(masses))));
        }

        /// <summary>Sets a node's viscosity (≥ 0); refused if it would put dt past the critical timestep.</summary>
        public void SetViscosity(int node, float viscosity)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_set_viscosity(s.Ptr, Node(node), viscosity));
        }

        /// <summary>Sets every node's viscosity, all checked before any changes.</summary>
        public void SetViscosities(float[] viscosities)
        {
            using (var s = Enter())
            fixed (float* p = viscosities)
                SpringwaterException.Check(
                    Native.sw_surface_set_viscosities(s.Ptr, p, Size(Count(viscosities))));
        }

        /// <summary>Every node's viscosity, the absorbing frame's ramp included.</summary>
        public void WriteViscosities(float[] viscosities)
        {
            using (var s = Enter())
            fixed (float* p = viscosities)
                SpringwaterException.Check(
                    Native.sw_surface_write_viscosities(s.Ptr, p, Size(Count(viscosities))));
        }

        // ---- Springs ----

        /// <summary>
        /// The rest length and coefficient of the spring of <paramref name="family"/>
        /// (Native.SW_FAMILY_*) whose origin is <paramref name="node"/>; refused for a spring
        /// the grid does not have.
        /// </summary>
        public void Spring(int family, int node, out float rest, out float stiffness)
        {
            float* pair = stackalloc float[2];
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_spring(s.Ptr, family, Node(node), pair));
            rest = pair[0];
            stiffness = pair[1];
        }

        /// <summary>Sets a spring's rest length (≥ 0) and coefficient (> 0).</summary>
        public void SetSpring(int family, int node, float rest, float stiffness)
        {
            using (var s = Enter())
                SpringwaterException.Check(
                    Native.sw_surface_set_spring(s.Ptr, family, Node(node), rest, stiffness));
        }

        /// <summary>Adds a force to one node for the next step only, in the lattice's force units.</summary>
        public void AddForce(int node, float fx, float fy, float fz)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_add_force(s.Ptr, Node(node), fx, fy, fz));
        }

        /// <summary>Discards every force waiting for the next step (BodyForces' share among them).</summary>
        public void ClearForces()
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_clear_forces(s.Ptr));
        }

        /// <summary>Adds a velocity change to one free node now (an impulse divided by its mass).</summary>
        public void AddVelocity(int node, float dvx, float dvy, float dvz)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_add_velocity(s.Ptr, Node(node), dvx, dvy, dvz));
        }

        /// A node index for the C ABI; a negative one is refused here, where the C ABI's
        /// unsigned index cannot say it.
        static UIntPtr Node(int node)
        {
            if (node < 0)
                throw new SpringwaterException(
                    Native.SW_ERROR_INVALID_ARGUMENT, "node " + node + " is negative");
            return (UIntPtr)node;
        }
    }
}
