// springwater.h included from C++: every kind of declaration the header has (structs and
// their makers, opaque handles, constants, calls with pointers and lengths) used once, so
// that a C++ compiler checks them; the program runs against the static library.
#include "springwater.h"

#include <cstdio>

int main() {
    SwParams params = sw_params_default();
    SwSurface *surface = nullptr;
    if (sw_surface_create(&params, &surface) != SW_OK)
        return 1;

    // A box as a hull mesh: vertex i has x, y and z from its bits 0, 1 and 2.
    float xyz[24];
    for (int i = 0; i < 8; i++)
        for (int k = 0; k < 3; k++)
            xyz[3 * i + k] = (i >> k) & 1 ? 1.0f : -1.0f;
    const uint32_t triangles[36] = {0, 4, 6, 0, 6, 2, 1, 7, 5, 1, 3, 7, 0, 1, 5, 0, 5, 4,
                                    2, 7, 3, 2, 6, 7, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};
    SwHull *hull = nullptr;
    float volume = 0.0f;
    SwFloater body = sw_floater_box(1.0f, 1.0f, 1.0f, 4.0f, 64.0f, 0.0f, 64.0f);
    SwFloaterId id = 0;
    SwBodyForces push = sw_body_forces_default();
    int failed = 0;
    failed |= sw_hull_create(xyz, 8, triangles, 12, &hull) != SW_OK;
    failed |= sw_hull_volume(hull, &volume) != SW_OK || volume != 8.0f;
    failed |= sw_floater_hull(hull, 4.0f, 64.0f, 0.0f, 64.0f, &body) != SW_OK;
    failed |= body.shape != SW_SHAPE_HULL || body.orientation[3] != 1.0f;
    failed |= sw_surface_add_hull_floater(surface, hull, &body, &id) != SW_OK;
    failed |= sw_surface_push_floater_at(surface, id, 0.0f, 1.0f, 0.0f, 65.0f, 0.0f, 64.0f) != SW_OK;
    failed |= sw_surface_hull_body_forces(surface, hull, &body, 1.0f / 60.0f, &push) != SW_OK;
    failed |= push.force[1] <= 0.0f;
    failed |= sw_surface_body_forces(surface, &body, 1.0f / 60.0f, &push) != SW_ERROR_INVALID_ARGUMENT;
    failed |= sw_floater_box(1, 1, 1, 1, 0, 0, 0).struct_size <= SW_FLOATER_SIZE_V1;
    sw_hull_destroy(hull);
    sw_surface_destroy(surface);
    if (failed)
        std::printf("the C++ program's calls failed\n");
    return failed;
}
