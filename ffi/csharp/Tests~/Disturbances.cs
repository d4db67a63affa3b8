// Rain and wakes through the C# package: made, applied before every substep by
// AdvanceWith, read and moved; the state they make is printed for ffi/tests/csharp.rs to
// recompute through the Rust API.
using System;
using Springwater;

static unsafe partial class Runner
{
    /// Kept in step with `disturbances()` in ffi/tests/csharp.rs.
    static void Disturbances()
    {
        using (var w = new WaterSurface(48, 40))
        using (var rain = new Rain(20, 7, 1, 2.5f, 0.5f))
        using (var wake = new Wake(new float[] { 10, 10, 38, 10, 38, 30 }, 30, 2, 1))
        using (var circle = Wake.Circle(w, 12, 60, 2.5f, 1.5f))
        {
            uint steps = 0;
            for (int frame = 0; frame < 30; frame++)
                steps += w.AdvanceWith(1f / 60f, rain, wake, circle);
            Assert(steps == 30, "a step a frame");
            Assert(rain.Fallen > 0 && Math.Abs(rain.Time - 0.5) < 1e-5, "rain fell for half a second");
            float x, z;
            wake.Position(out x, out z);
            Value("wake_position", Hex(x) + Hex(z));
            Value("rain_fallen", rain.Fallen.ToString());
            wake.Translate(-2, 1);
            rain.SetRate(0);
            w.AdvanceWith(0.25f, rain, wake, circle);
            Value("disturbed_hash", w.StateHash().ToString("x16"));

            ulong before = w.StateHash();
            Refused("listed_twice", Native.SW_ERROR_BUSY, "listed twice", () => w.AdvanceWith(0.1f, rain, rain));
            Refused("rain_rate_negative", Native.SW_ERROR_INVALID_ARGUMENT, "rate", () => rain.SetRate(-1));
            Refused("wake_one_place", Native.SW_ERROR_INVALID_ARGUMENT, "path",
                () => new Wake(new float[] { 1, 1, 1, 1 }, 60, 2.5f, 1.5f));
            Refused("rain_radii_reversed", Native.SW_ERROR_INVALID_ARGUMENT, "radius_max",
                () => new Rain(5, 1, 3, 1, 0.5f));
            var gone = new Rain(5, 1, 1.5f, 3, 0.6f);
            gone.Dispose();
            gone.Dispose();
            Refused("disposed_rain", Native.SW_ERROR_INVALID_HANDLE, "not a live", () => w.AdvanceWith(0.1f, gone));
            Assert(w.StateHash() == before, "refusals change nothing");
            Assert(w.AdvanceWith(0.1f) >= 0, "no disturbance is an ordinary frame");
        }
    }
}
