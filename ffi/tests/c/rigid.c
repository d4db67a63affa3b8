/* A C client of springwater.h's rigid bodies, written only from the header: a box heeled
 * 15° rights itself as a built-in floating body, and again in the client's own explicit
 * 60 Hz integrator driven by sw_surface_body_forces, as a game engine would; the same box
 * as a hull mesh; a client built against the version 1 SwFloater; bad input; the
 * library's boat floating through rain and a wake.
 *
 * It prints `key value` lines that tests/c_client.rs compares with the Rust API, and
 * exits non-zero (after printing `FAIL ...`) when a check here fails. */

#include "springwater.h"
#include "check.h"

#include <float.h>
#include <inttypes.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#define FRAME (1.0f / 60.0f)
#define FRAMES 600 /* ten seconds */

/* The box: 6 × 1.5 × 3 at half the water's density, wide across x so it is stiff in roll
 * (metacentric height GM = B²/12T + T/2 − H/2 = 4.0). */
static const float HALF[3] = {3.0f, 0.75f, 1.5f};

/* 15° about the world's x axis, (x, y, z, w): sin and cos of 7.5°. */
static const float HEELED[4] = {0.13052619f, 0.0f, 0.0f, 0.9914449f};

/* A 48 × 48 surface at the defaults. */
static SwSurface *water(void) {
    SwParams params = sw_params_default();
    params.cols = 48;
    params.rows = 48;
    SwSurface *surface = NULL;
    OK(sw_surface_create(&params, &surface));
    return surface;
}

static SwBuoyancy buoyancy_of(SwSurface *surface) {
    SwBuoyancy buoyancy = sw_buoyancy_default();
    OK(sw_surface_buoyancy(surface, &buoyancy));
    return buoyancy;
}

/* The box, upright at (24, 0, 24), the centre of the pool. */
static SwFloater the_box(SwSurface *surface) {
    float mass = 0.5f * buoyancy_of(surface).density * 8.0f * HALF[0] * HALF[1] * HALF[2];
    return sw_floater_box(HALF[0], HALF[1], HALF[2], mass, 24.0f, 0.0f, 24.0f);
}

/* The angle in degrees between the body's up axis and the world's: the y of the body's y
 * axis turned by the quaternion is 1 − 2(x² + z²). */
static float heel(const SwFloater *f) {
    const float *q = f->orientation;
    float up = 1.0f - 2.0f * (q[0] * q[0] + q[2] * q[2]);
    up = up > 1.0f ? 1.0f : (up < -1.0f ? -1.0f : up);
    return acosf(up) * 57.2957795f;
}

static SwFloater floater_of(SwSurface *surface, SwFloaterId id) {
    SwFloater f = {.struct_size = sizeof f};
    OK(sw_surface_floater(surface, id, &f));
    return f;
}

/* Ten seconds of frames; returns the largest heel over the last second. */
static float worst_late_heel(SwSurface *surface, SwFloaterId id) {
    float worst = 0.0f;
    for (int frame = 0; frame < FRAMES; frame++) {
        OK(sw_surface_advance(surface, FRAME, NULL));
        SwFloater f = floater_of(surface, id);
        if (frame == 0) {
            /* The water turns it back: about −x, against the heel. */
            CHECK(f.angular_velocity[0] < 0.0f);
            CHECK(f.water_torque[0] < 0.0f);
        }
        if (frame >= FRAMES - 60 && heel(&f) > worst)
            worst = heel(&f);
    }
    return worst;
}

/* (a) The built-in body: added heeled, stepped by the surface, read back. */
static void built_in_box_rights_itself(void) {
    SwSurface *surface = water();
    SwFloater box = the_box(surface);
    memcpy(box.orientation, HEELED, sizeof HEELED);
    SwFloaterId id = 99;
    OK(sw_surface_add_floater(surface, &box, &id));
    SwFloater added = floater_of(surface, id);
    CHECK(fabsf(heel(&added) - 15.0f) < 0.01f);
    float late = worst_late_heel(surface, id);
    printf("built_in_late_heel %.3f\n", late);
    CHECK(late < 1.0f);
    SwFloater f = floater_of(surface, id);
    printf("righted_orientation %08" PRIx32 " %08" PRIx32 " %08" PRIx32 " %08" PRIx32 "\n",
           float_bits(f.orientation[0]), float_bits(f.orientation[1]),
           float_bits(f.orientation[2]), float_bits(f.orientation[3]));
    printf("righted_position %08" PRIx32 "\n", float_bits(f.position[1]));
    sw_surface_destroy(surface);
}

/* Row-major rotation matrix of the unit quaternion q = (x, y, z, w). */
static void rotation(const float q[4], float r[9]) {
    float x = q[0], y = q[1], z = q[2], w = q[3];
    r[0] = 1 - 2 * (y * y + z * z), r[1] = 2 * (x * y - z * w), r[2] = 2 * (x * z + y * w);
    r[3] = 2 * (x * y + z * w), r[4] = 1 - 2 * (x * x + z * z), r[5] = 2 * (y * z - x * w);
    r[6] = 2 * (x * z - y * w), r[7] = 2 * (y * z + x * w), r[8] = 1 - 2 * (x * x + y * y);
}

/* Solves the symmetric 3 × 3 system m x = b (Cramer's rule; m is positive definite). */
static void solve3(const float m[9], const float b[3], float x[3]) {
    float det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                m[2] * (m[3] * m[7] - m[4] * m[6]);
    for (int k = 0; k < 3; k++) {
        float c[9];
        memcpy(c, m, sizeof c);
        for (int row = 0; row < 3; row++)
            c[3 * row + k] = b[row];
        x[k] = (c[0] * (c[4] * c[8] - c[5] * c[7]) - c[1] * (c[3] * c[8] - c[5] * c[6]) +
                c[2] * (c[3] * c[7] - c[4] * c[6])) /
               det;
    }
}

/* One tick of a game engine's explicit integrator: semi-implicit Euler (the velocities
 * from the forces, then the pose from the new velocities), the orientation turned by the
 * angular velocity and normalised. `inertia` is in the body's axes. */
static void engine_step(SwFloater *body, const SwBodyForces *push, float gravity,
                        const float inertia[9], float dt) {
    for (int k = 0; k < 3; k++)
        body->velocity[k] += dt * push->force[k] / body->mass;
    body->velocity[1] -= dt * gravity;
    /* Angular acceleration R I⁻¹ Rᵀ τ: the torque into the body's axes, solved, back. */
    float r[9], local[3], alpha_local[3];
    rotation(body->orientation, r);
    for (int k = 0; k < 3; k++)
        local[k] = r[k] * push->torque[0] + r[3 + k] * push->torque[1] + r[6 + k] * push->torque[2];
    solve3(inertia, local, alpha_local);
    for (int k = 0; k < 3; k++) {
        float alpha = r[3 * k] * alpha_local[0] + r[3 * k + 1] * alpha_local[1] +
                      r[3 * k + 2] * alpha_local[2];
        body->angular_velocity[k] += dt * alpha;
        body->position[k] += dt * body->velocity[k];
    }
    /* q += dt/2 · (ω, 0) q, then normalised. */
    const float *w = body->angular_velocity;
    float *q = body->orientation;
    float dq[4] = {
        q[3] * w[0] + (w[1] * q[2] - w[2] * q[1]),
        q[3] * w[1] + (w[2] * q[0] - w[0] * q[2]),
        q[3] * w[2] + (w[0] * q[1] - w[1] * q[0]),
        -(w[0] * q[0] + w[1] * q[1] + w[2] * q[2]),
    };
    float norm = 0.0f;
    for (int k = 0; k < 4; k++) {
        q[k] += 0.5f * dt * dq[k];
        norm += q[k] * q[k];
    }
    norm = sqrtf(norm);
    for (int k = 0; k < 4; k++)
        q[k] /= norm;
}

/* (b) The body in the client's own engine: the surface only answers its forces. */
static void engine_box_rights_itself(void) {
    SwSurface *surface = water();
    float gravity = buoyancy_of(surface).gravity;
    SwFloater body = the_box(surface);
    memcpy(body.orientation, HEELED, sizeof HEELED);
    /* The maker read back the box's inertia for its mass: the engine's too. */
    float inertia[9];
    memcpy(inertia, body.inertia, sizeof inertia);
    CHECK(body.has_inertia == 0 && inertia[0] > 0.0f && inertia[1] == 0.0f);
    SwBodyForces push = sw_body_forces_default();
    float worst = 0.0f, start = heel(&body);
    for (int frame = 0; frame < FRAMES; frame++) {
        OK(sw_surface_body_forces(surface, &body, FRAME, &push));
        if (frame == 0)
            CHECK(push.torque[0] < 0.0f); /* righting */
        engine_step(&body, &push, gravity, inertia, FRAME);
        OK(sw_surface_advance(surface, FRAME, NULL));
        CHECK(isfinite(body.position[1]) && isfinite(body.orientation[3]));
        if (frame >= FRAMES - 60 && heel(&body) > worst)
            worst = heel(&body);
    }
    float speed = sqrtf(body.velocity[0] * body.velocity[0] + body.velocity[1] * body.velocity[1] +
                        body.velocity[2] * body.velocity[2]);
    printf("engine_late_heel %.3f\n", worst);
    CHECK(fabsf(start - 15.0f) < 0.01f && worst < 1.0f);
    CHECK(speed < 0.1f);
    /* Floating at about half its height (the water under it moves a little). */
    CHECK(fabsf(body.position[1]) < 0.15f);
    sw_surface_destroy(surface);
}

/* The box as a closed mesh: vertex i has x from bit 0, y from bit 1, z from bit 2 (minus
 * or plus the half extent); two triangles a face, counter-clockwise seen from outside. */
static const uint32_t BOX_TRIANGLES[36] = {
    0, 4, 6, 0, 6, 2, /* −x */ 1, 7, 5, 1, 3, 7, /* +x */
    0, 1, 5, 0, 5, 4, /* −y */ 2, 7, 3, 2, 6, 7, /* +y */
    0, 2, 3, 0, 3, 1, /* −z */ 4, 5, 7, 4, 7, 6, /* +z */
};

static SwHull *box_hull(void) {
    float xyz[24];
    for (int i = 0; i < 8; i++)
        for (int k = 0; k < 3; k++)
            xyz[3 * i + k] = (i >> k) & 1 ? HALF[k] : -HALF[k];
    SwHull *hull = NULL;
    OK(sw_hull_create(xyz, 8, BOX_TRIANGLES, 12, &hull));
    CHECK(hull != NULL);
    return hull;
}

static float length3(const float v[3]) {
    return sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* (c) The box as a hull: the same forces as the built-in box, and it rights itself. */
static void hull_box_rights_itself(void) {
    SwSurface *surface = water();
    SwHull *hull = box_hull();
    float volume = 0.0f;
    OK(sw_hull_volume(hull, &volume));
    CHECK(volume == 8.0f * HALF[0] * HALF[1] * HALF[2]);
    SwFloater box = the_box(surface);
    SwFloater mesh = {.struct_size = sizeof mesh};
    OK(sw_floater_hull(hull, box.mass, 24.0f, 0.0f, 24.0f, &mesh));
    CHECK(mesh.shape == SW_SHAPE_HULL && mesh.has_inertia == 0);
    for (int k = 0; k < 9; k++)
        CHECK(fabsf(mesh.inertia[k] - box.inertia[k]) <= 1e-4f * box.inertia[0]);
    memcpy(box.orientation, HEELED, sizeof HEELED);
    memcpy(mesh.orientation, HEELED, sizeof HEELED);

    SwBodyForces of_box = sw_body_forces_default(), of_mesh = sw_body_forces_default();
    OK(sw_surface_body_forces(surface, &box, FRAME, &of_box));
    OK(sw_surface_hull_body_forces(surface, hull, &mesh, FRAME, &of_mesh));
    float df[3], dt[3];
    for (int k = 0; k < 3; k++) {
        df[k] = of_mesh.force[k] - of_box.force[k];
        dt[k] = of_mesh.torque[k] - of_box.torque[k];
    }
    CHECK(length3(df) < 0.02f * length3(of_box.force));
    CHECK(length3(dt) < 0.05f * length3(of_box.torque));
    sw_surface_destroy(surface);

    surface = water();
    SwFloaterId id = 99;
    OK(sw_surface_add_hull_floater(surface, hull, &mesh, &id));
    /* The surface keeps the mesh: the client may free its hull at once. */
    sw_hull_destroy(hull);
    SwFloater back = floater_of(surface, id);
    CHECK(back.shape == SW_SHAPE_HULL && back.radius == 0.0f && back.half_extents[0] == 0.0f);
    /* Set with SW_SHAPE_HULL keeps the body's mesh. */
    back.drag = 8.0f;
    OK(sw_surface_set_floater(surface, id, &back));
    float late = worst_late_heel(surface, id);
    printf("hull_late_heel %.3f\n", late);
    CHECK(late < 1.0f);
    CHECK(floater_of(surface, id).shape == SW_SHAPE_HULL);
    sw_surface_destroy(surface);
}

/* SwFloater as version 1 of the header declared it: 80 bytes, up to water_force. */
typedef struct {
    uint32_t struct_size;
    SwShape shape;
    float radius, half_extents[3], mass, drag, position[3], velocity[3], push[3], water_force[3];
} SwFloaterV1;

/* (d) A client built against version 1: its struct is taken and filled as far as it goes.
 * It is allocated at exactly its size, so AddressSanitizer and Valgrind see any access
 * past it. */
static void version_1_client(void) {
    CHECK(sizeof(SwFloaterV1) == SW_FLOATER_SIZE_V1);
    SwSurface *surface = water();
    SwFloater current = the_box(surface);
    SwFloaterV1 *old = malloc(sizeof *old);
    memcpy(old, &current, sizeof *old);
    old->struct_size = SW_FLOATER_SIZE_V1;
    SwFloaterId id = 99;
    OK(sw_surface_add_floater(surface, (const SwFloater *)old, &id));
    SwFloater added = floater_of(surface, id);
    CHECK(added.orientation[3] == 1.0f && added.orientation[0] == 0.0f);
    /* A current client turns it; the old one moves it and keeps the turn. */
    memcpy(added.orientation, HEELED, sizeof HEELED);
    OK(sw_surface_set_floater(surface, id, &added));
    old->velocity[0] = 1.0f;
    OK(sw_surface_set_floater(surface, id, (const SwFloater *)old));
    SwFloater now = floater_of(surface, id);
    CHECK(now.velocity[0] == 1.0f && fabsf(heel(&now) - 15.0f) < 0.01f);
    OK(sw_surface_advance(surface, FRAME, NULL));
    OK(sw_surface_floater(surface, id, (SwFloater *)old));
    CHECK(old->struct_size == SW_FLOATER_SIZE_V1 && old->water_force[1] > 0.0f);
    SwBodyForces push = sw_body_forces_default();
    OK(sw_surface_body_forces(surface, (const SwFloater *)old, FRAME, &push));
    CHECK(push.force[1] > 0.0f);
    old->struct_size = SW_FLOATER_SIZE_V1 - 4;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_floater(surface, id, (SwFloater *)old));
    free(old);
    sw_surface_destroy(surface);
}

/* (e) Bad input: refused with a message, nothing changed. */
static void bad_input(void) {
    SwSurface *surface = water();
    SwFloater box = the_box(surface);
    SwFloaterId id = 99;
    OK(sw_surface_add_floater(surface, &box, &id));
    SwBodyForces push = sw_body_forces_default();
    float xyz[24] = {0};
    SwHull *hull = NULL;

    /* Meshes: NULL arrays, lengths past memory, an open mesh, indices out of range. */
    FAILS(SW_ERROR_NULL_POINTER, sw_hull_create(NULL, 8, BOX_TRIANGLES, 12, &hull));
    FAILS(SW_ERROR_NULL_POINTER, sw_hull_create(xyz, 8, NULL, 12, &hull));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_hull_create(xyz, SIZE_MAX, BOX_TRIANGLES, 12, &hull));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_hull_create(xyz, 8, BOX_TRIANGLES, 11, &hull));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_hull_create(xyz, 8, BOX_TRIANGLES, 0, &hull));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_hull_create(xyz, 6, BOX_TRIANGLES, 12, &hull));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_hull_create(xyz, 8, BOX_TRIANGLES, 12, &hull)); /* flat */
    CHECK(hull == NULL);
    SwHull *real = box_hull();
    FAILS(SW_ERROR_NULL_POINTER, sw_hull_create(xyz, 8, BOX_TRIANGLES, 12, NULL));
    FAILS(SW_ERROR_NULL_POINTER, sw_hull_volume(real, NULL));
    FAILS(SW_ERROR_NULL_POINTER, sw_hull_volume(NULL, xyz));

    /* Hull bodies: a hull body needs its mesh, and a mesh a hull body. */
    SwFloater mesh = {.struct_size = sizeof mesh};
    OK(sw_floater_hull(real, box.mass, 24.0f, 0.0f, 24.0f, &mesh));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_add_floater(surface, &mesh, &id));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_body_forces(surface, &mesh, FRAME, &push));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_add_hull_floater(surface, real, &box, &id));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_floater(surface, id, &mesh)); /* a box */
    SwHull *made_up = (SwHull *)(uintptr_t)0x5eed;
    FAILS(SW_ERROR_INVALID_HANDLE, sw_surface_add_hull_floater(surface, made_up, &mesh, &id));
    FAILS(SW_ERROR_INVALID_HANDLE, sw_hull_volume(made_up, xyz));
    /* A surface's handle is no hull's, and a hull's no surface's. */
    FAILS(SW_ERROR_INVALID_HANDLE, sw_hull_volume((SwHull *)surface, xyz));
    size_t count = 0;
    FAILS(SW_ERROR_INVALID_HANDLE, sw_surface_floater_count((SwSurface *)real, &count));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_add_hull_floater(surface, NULL, &mesh, &id));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_hull_body_forces(surface, real, NULL, FRAME, &push));
    SwFloater small = {.struct_size = 3};
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_floater_hull(real, 1.0f, 0.0f, 0.0f, 0.0f, &small));
    FAILS(SW_ERROR_NULL_POINTER, sw_floater_hull(real, 1.0f, 0.0f, 0.0f, 0.0f, NULL));
    sw_hull_destroy(real);
    FAILS(SW_ERROR_INVALID_HANDLE, sw_hull_volume(real, xyz));
    sw_hull_destroy(NULL);

    /* Poses, velocities and inertias a rigid body cannot have. */
    SwFloater bad = box;
    bad.orientation[3] = 2.0f; /* not a unit quaternion */
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_add_floater(surface, &bad, &id));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_floater(surface, id, &bad));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_body_forces(surface, &bad, FRAME, &push));
    bad = box;
    bad.orientation[1] = NAN;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_add_floater(surface, &bad, &id));
    bad = box;
    bad.angular_velocity[2] = INFINITY;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_add_floater(surface, &bad, &id));
    bad = box;
    bad.has_inertia = 2;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_add_floater(surface, &bad, &id));
    bad = box;
    bad.has_inertia = 1;
    bad.inertia[1] = bad.inertia[0]; /* not symmetric */
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_add_floater(surface, &bad, &id));
    bad.inertia[3] = bad.inertia[0]; /* symmetric, not positive definite */
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_add_floater(surface, &bad, &id));
    bad = box;
    bad.has_inertia = 1;
    bad.inertia[0] = 3.0f * (bad.inertia[4] + bad.inertia[8]); /* past the triangle rule */
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_add_floater(surface, &bad, &id));
    bad.inertia[0] = 0.5f * (bad.inertia[4] + bad.inertia[8]); /* a real body's */
    OK(sw_surface_set_floater(surface, id, &bad));
    CHECK(floater_of(surface, id).has_inertia == 1);

    /* body_forces: the tick, the out-struct's size, NULLs. */
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_body_forces(surface, &box, 0.0f, &push));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_body_forces(surface, &box, NAN, &push));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_body_forces(surface, &box, 1.5f, &push));
    SwBodyForces unset = {0};
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_body_forces(surface, &box, FRAME, &unset));
    CHECK(unset.force[1] == 0.0f);
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_body_forces(surface, &box, FRAME, NULL));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_body_forces(surface, NULL, FRAME, &push));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_body_forces(NULL, &box, FRAME, &push));

    /* Pushes at a point: a torque about the centre of mass, finite only. */
    OK(sw_surface_push_floater_at(surface, id, 0.0f, 3.0f, 0.0f, 26.0f, 0.0f, 24.0f));
    SwFloater pushed = floater_of(surface, id);
    CHECK(pushed.push[1] == 3.0f && pushed.push_torque[2] == 6.0f);
    FAILS(SW_ERROR_INVALID_ARGUMENT,
          sw_surface_push_floater_at(surface, id, 0.0f, 3.0f, 0.0f, NAN, 0.0f, 24.0f));
    FAILS(SW_ERROR_INVALID_ARGUMENT,
          sw_surface_push_floater_at(surface, id, FLT_MAX, 0.0f, 0.0f, 24.0f, FLT_MAX, 24.0f));
    FAILS(SW_ERROR_NO_SUCH_FLOATER,
          sw_surface_push_floater_at(surface, 12345, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f));
    SwFloater after = floater_of(surface, id);
    CHECK(memcmp(&after, &pushed, sizeof after) == 0); /* the refusals changed nothing */
    sw_surface_destroy(surface);
}

/* The library's boat, centred on its centroid, floats through rain and a circling wake
 * applied by sw_surface_advance_with; its mesh is read back the C way (the count first). */
static void boat_in_rain_and_a_wake(void) {
    SwSurface *surface = water();
    SwBoatShape shape = sw_boat_shape_default();
    shape.stations = 12;
    shape.segments = 4;
    SwHull *keel = NULL, *boat = NULL;
    OK(sw_hull_boat(&shape, &keel));
    OK(sw_hull_centred(keel, &boat));
    sw_hull_destroy(keel);
    float centroid[3] = {1.0f, 1.0f, 1.0f};
    OK(sw_hull_centroid(boat, centroid));
    CHECK(fabsf(centroid[0]) < 1e-4f && fabsf(centroid[1]) < 1e-4f && fabsf(centroid[2]) < 1e-4f);

    size_t vertices = 0, triangles = 0;
    OK(sw_hull_vertices(boat, NULL, 0, &vertices));
    OK(sw_hull_triangles(boat, NULL, 0, &triangles));
    CHECK(triangles == 4 * 12 * 4 + 2 * 12 + 2 * 4);
    float *xyz = malloc(3 * vertices * sizeof *xyz);
    uint32_t *indices = malloc(3 * triangles * sizeof *indices);
    FAILS(SW_ERROR_BUFFER_TOO_SMALL, sw_hull_vertices(boat, xyz, 3 * vertices - 1, &vertices));
    OK(sw_hull_vertices(boat, xyz, 3 * vertices, &vertices));
    OK(sw_hull_triangles(boat, indices, 3 * triangles, &triangles));
    /* The mesh read back makes the same hull. */
    SwHull *again = NULL;
    OK(sw_hull_create(xyz, vertices, indices, triangles, &again));
    float volume = 0.0f, volume_again = -1.0f, radius = 0.0f;
    OK(sw_hull_volume(boat, &volume));
    OK(sw_hull_volume(again, &volume_again));
    CHECK(volume > 0.0f && volume == volume_again);
    OK(sw_hull_bounding_radius(boat, &radius));
    CHECK(radius > 0.5f * shape.length && radius < shape.length);
    sw_hull_destroy(again);
    free(xyz);
    free(indices);

    SwBuoyancy buoyancy = buoyancy_of(surface);
    SwFloater body = {.struct_size = sizeof body};
    OK(sw_floater_hull(boat, 0.4f * buoyancy.density * volume, 24.0f, 0.0f, 24.0f, &body));
    SwFloaterId id = 0;
    OK(sw_surface_add_hull_floater(surface, boat, &body, &id));
    sw_hull_destroy(boat); /* the surface keeps the mesh */

    SwDisturbance *rain = NULL, *wake = NULL;
    OK(sw_rain_create(30.0f, 11, 1.0f, 2.0f, 0.5f, &rain));
    OK(sw_wake_circle(surface, 14.0f, 40.0f, 2.0f, 1.0f, &wake));
    SwDisturbance *both[2] = {rain, wake};
    uint32_t steps = 0;
    for (int frame = 0; frame < 120; frame++) {
        uint32_t taken = 0;
        OK(sw_surface_advance_with(surface, FRAME, both, 2, &taken));
        steps += taken;
    }
    CHECK(steps == 120);
    uint64_t fallen = 0;
    OK(sw_rain_fallen(rain, &fallen));
    CHECK(fallen > 30);
    float at[2];
    OK(sw_wake_position(wake, at));
    CHECK(fabsf(hypotf(at[0] - 23.5f, at[1] - 23.5f) - 14.0f) < 0.5f);
    SwFloater afloat = floater_of(surface, id);
    CHECK(isfinite(afloat.position[1]) && fabsf(afloat.position[1]) < 1.0f);
    float bow[3];
    OK(sw_floater_velocity_at(&afloat, afloat.position[0] + 3.0f, afloat.position[1],
                              afloat.position[2], bow));
    CHECK(isfinite(bow[0]) && isfinite(bow[1]) && isfinite(bow[2]));

    /* Refusals: the same rain twice, the wrong kind, a destroyed handle. */
    SwDisturbance *twice[2] = {rain, rain};
    FAILS(SW_ERROR_BUSY, sw_surface_advance_with(surface, FRAME, twice, 2, NULL));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_rain_fallen(wake, &fallen));
    sw_disturbance_destroy(rain);
    FAILS(SW_ERROR_INVALID_HANDLE, sw_surface_advance_with(surface, FRAME, both, 2, NULL));
    sw_disturbance_destroy(wake);
    sw_surface_destroy(surface);
}

int main(void) {
    built_in_box_rights_itself();
    engine_box_rights_itself();
    hull_box_rights_itself();
    version_1_client();
    bad_input();
    boat_in_rain_and_a_wake();
    if (failures == 0)
        printf("rigid_checks passed\n");
    return failures == 0 ? 0 : 1;
}
