// The hulls the library makes (the boat, a box, a hull on its centroid) and what they are,
// a point's velocity on a body and bounding radii, through the C# package; the values are
// printed for ffi/tests/csharp.rs to recompute through the Rust API.
using System;
using Springwater;

static unsafe partial class Runner
{
    /// Kept in step with `shapes()` in ffi/tests/csharp.rs.
    static void Shapes()
    {
        const int Arg = Native.SW_ERROR_INVALID_ARGUMENT;
        var shape = SwBoatShape.Default();
        Assert(shape.stations == 40 && shape.segments == 12, "the default boat");
        shape.stations = 12;
        shape.segments = 4;
        using (Hull boat = Hull.Boat(shape))
        using (Hull centred = boat.Centred())
        {
            int[] triangles = boat.Triangles();
            float[] xyz = boat.Vertices();
            Assert(triangles.Length == 3 * (4 * 12 * 4 + 2 * 12 + 2 * 4), "the boat's triangles");
            Value("boat_mesh", Fnv(xyz, xyz.Length).ToString("x16"));
            Value("boat_volume", Hex(boat.Volume));
            Value("boat_centroid", Hex(boat.Centroid.x) + Hex(boat.Centroid.y) + Hex(boat.Centroid.z));
            Assert(boat.Centroid.y > 0, "the boat's origin is on its keel");
            Assert(Math.Abs(centred.Centroid.y) < 1e-4, "the centred boat's centroid is at its origin");
            Value("centred_radius", Hex(centred.BoundingRadius));
            // A hull made from the centred boat's mesh is the same hull.
            using (var again = new Hull(centred.Vertices(), centred.Triangles()))
                Assert(again.Volume == centred.Volume, "the mesh read back makes the same hull");
            using (var water = new WaterSurface(32, 32))
            {
                ulong id = water.AddHullFloater(centred, centred.Floater(0.5f * centred.Volume, 16, 0, 16));
                Assert(water.Floater(id).shape == Native.SW_SHAPE_HULL, "a boat floats");
            }
        }
        using (Hull box = Hull.Cuboid(1, 0.5f, 2))
        {
            Assert(box.Volume == 8 && box.Vertices().Length == 24 && box.Triangles().Length == 36,
                "a box hull: 8 vertices, 12 triangles");
            Assert(box.BoundingRadius == (float)Math.Sqrt(1 + 0.25 + 4), "the box's corner");
        }
        Refused("hull_cuboid_negative", Arg, "half", () => Hull.Cuboid(-1, 1, 1));
        shape.stations = 1;
        Refused("boat_one_station", Arg, "stations", () => Hull.Boat(shape));

        SwFloater body = SwFloater.Box(1, 0.5f, 2, 3, 4, 0, 5);
        body.Velocity = new Float3(1, -0.5f, 0.25f);
        body.AngularVelocity = new Float3(0.3f, 1.5f, -0.2f);
        Float3 v = body.VelocityAt(5, 0.5f, 3);
        Value("point_velocity", Hex(v.x) + Hex(v.y) + Hex(v.z));
        Value("box_bounding_radius", Hex(body.BoundingRadius()));
        Assert(SwFloater.Sphere(1.5f, 2, 0, 0, 0).BoundingRadius() == 1.5f, "a sphere's radius");
        body.AngularVelocity = new Float3(float.NaN, 0, 0);
        Refused("velocity_not_finite", Arg, "angular_velocity", () => body.VelocityAt(0, 0, 0));
    }
}
