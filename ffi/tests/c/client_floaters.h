/* Part of client.c, included by it once after its own includes: floating bodies on open
 * water through the C ABI, the same as tests/c_client.rs runs through the Rust API, and
 * the snapshots and rollbacks they take part in. */

#ifndef SPRINGWATER_TEST_CLIENT_FLOATERS_H
#define SPRINGWATER_TEST_CLIENT_FLOATERS_H

/* ---- Floating bodies on open water, the same as tests/c_client.rs runs through the Rust
 * API. ---- */

/* A body's fields: radius, half extents, mass, drag, position, velocity, push, water force,
 * orientation, angular velocity, push torque, water torque. */
#define FLOATER_FLOATS 31
static void floater_floats(const SwFloater *f, float out[FLOATER_FLOATS]) {
    out[0] = f->radius;
    memcpy(&out[1], f->half_extents, 12);
    out[4] = f->mass;
    out[5] = f->drag;
    memcpy(&out[6], f->position, 12);
    memcpy(&out[9], f->velocity, 12);
    memcpy(&out[12], f->push, 12);
    memcpy(&out[15], f->water_force, 12);
    memcpy(&out[18], f->orientation, 16);
    memcpy(&out[22], f->angular_velocity, 12);
    memcpy(&out[25], f->push_torque, 12);
    memcpy(&out[28], f->water_torque, 12);
}

/* FNV-1a over every body's fields, in the order of sw_surface_floater_ids. */
static uint64_t floaters_fingerprint(SwSurface *surface) {
    SwFloaterId ids[8];
    size_t count = 0;
    OK(sw_surface_floater_ids(surface, ids, 8, &count));
    float floats[8 * FLOATER_FLOATS];
    for (size_t k = 0; k < count && k < 8; k++) {
        SwFloater f = {.struct_size = sizeof f};
        OK(sw_surface_floater(surface, ids[k], &f));
        floater_floats(&f, &floats[FLOATER_FLOATS * k]);
    }
    return fingerprint(floats, FLOATER_FLOATS * (count < 8 ? count : 8));
}

/* The whole state's bytes (a snapshot), malloc'd; its size goes to `size`. */
static uint8_t *state_of(SwSurface *surface, size_t *size) {
    *size = 0;
    OK(sw_surface_save(surface, NULL, 0, size));
    uint8_t *bytes = malloc(*size);
    OK(sw_surface_save(surface, bytes, *size, size));
    return bytes;
}

static int same_state(SwSurface *surface, const uint8_t *bytes, size_t size) {
    size_t now_size = 0;
    uint8_t *now = state_of(surface, &now_size);
    int same = now_size == size && memcmp(now, bytes, size) == 0;
    free(now);
    return same;
}

static void floating_bodies(void) {
    /* An absorbing boundary through SwParams; its parameters read back as they were given,
     * and build the same surface again. */
    SwParams params = sw_params_default();
    CHECK(params.absorbing_width == 32);
    params.cols = 32;
    params.rows = 28;
    params.boundary = SW_BOUNDARY_ABSORBING;
    params.absorbing_width = 6;
    SwSurface *open = NULL;
    OK(sw_surface_create(&params, &open));
    /* An output struct says its size too: one without it is refused and left as it was. */
    SwParams read_back = {0};
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_params(open, &read_back));
    CHECK(read_back.cols == 0 && read_back.rows == 0);
    read_back.struct_size = sizeof read_back;
    OK(sw_surface_params(open, &read_back));
    CHECK(memcmp(&read_back, &params, sizeof params) == 0);
    SwSurface *again = NULL;
    OK(sw_surface_create(&read_back, &again));
    OK(sw_surface_params(again, &read_back));
    CHECK(memcmp(&read_back, &params, sizeof params) == 0);
    sw_surface_destroy(again);

    SwBuoyancy buoyancy = {.struct_size = sizeof buoyancy};
    OK(sw_surface_buoyancy(open, &buoyancy));
    CHECK(buoyancy.struct_size == sizeof buoyancy);
    SwBuoyancy old_name = {.struct_size = sizeof old_name};
    OK(sw_surface_get_buoyancy(open, &old_name)); /* the deprecated name, the same call */
    CHECK(memcmp(&old_name, &buoyancy, sizeof buoyancy) == 0);
    SwBuoyancy defaults = sw_buoyancy_default();
    CHECK(memcmp(&buoyancy, &defaults, sizeof buoyancy) == 0);
    printf("buoyancy %08" PRIx32 " %08" PRIx32 "\n", float_bits(buoyancy.gravity),
           float_bits(buoyancy.density));
    buoyancy.gravity = 69.12f; /* world units per second² */
    buoyancy.density = 1.1f;
    OK(sw_surface_set_buoyancy(open, &buoyancy));

    SwFloater ball = sw_floater_sphere(2.0f, 10.0f, 12.0f, 1.0f, 14.0f);
    CHECK(ball.shape == SW_SHAPE_SPHERE && ball.radius == 2.0f && ball.mass == 10.0f);
    CHECK(ball.position[1] == 1.0f && ball.velocity[0] == 0.0f && ball.push[2] == 0.0f);
    printf("floater_drag %08" PRIx32 "\n", float_bits(ball.drag));
    ball.velocity[0] = 1.2f; /* world units per second */
    ball.velocity[2] = -0.48f;
    SwFloaterId ball_id = 99, box_id = 99, spare_id = 99;
    OK(sw_surface_add_floater(open, &ball, &ball_id));
    SwFloater boxy = sw_floater_box(1.5f, 0.5f, 2.0f, 4.0f, 20.0f, 0.5f, 10.0f);
    CHECK(boxy.shape == SW_SHAPE_BOX && boxy.half_extents[2] == 2.0f && boxy.radius == 0.0f);
    OK(sw_surface_add_floater(open, &boxy, &box_id));
    SwFloater spare = sw_floater_sphere(1.0f, 1.0f, 8.0f, 0.0f, 8.0f);
    OK(sw_surface_add_floater(open, &spare, &spare_id));
    CHECK(ball_id == 0 && box_id == 1 && spare_id == 2);
    size_t count = 0;
    OK(sw_surface_floater_count(open, &count));
    CHECK(count == 3);
    OK(sw_surface_remove_floater(open, spare_id));
    FAILS(SW_ERROR_NO_SUCH_FLOATER, sw_surface_remove_floater(open, spare_id));
    FAILS(SW_ERROR_NO_SUCH_FLOATER, sw_surface_floater(open, spare_id, &spare));
    SwFloaterId ids[4] = {7, 7, 7, 7};
    OK(sw_surface_floater_ids(open, NULL, 0, &count));
    CHECK(count == 2);
    OK(sw_surface_floater_ids(open, ids, 4, &count));
    CHECK(count == 2 && ids[0] == ball_id && ids[1] == box_id && ids[2] == 7);
    /* Read back as added, with a zero water force. */
    SwFloater got = {0};
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_floater(open, ball_id, &got)); /* no size */
    CHECK(got.mass == 0.0f);
    got.struct_size = sizeof got;
    OK(sw_surface_floater(open, ball_id, &got));
    CHECK(memcmp(&got, &ball, sizeof got) == 0);

    /* Frames with a push, then a body set through get / set. */
    OK(sw_surface_drop_at(open, 16.0f, 14.0f, 0.5f, 2.0f));
    for (int frame = 0; frame < 40; frame++) {
        if (frame == 10) {
            OK(sw_surface_push_floater(open, ball_id, 288.0f, 0.0f, 115.2f));
        }
        OK(sw_surface_advance(open, 1.0f / 60.0f, NULL));
    }
    OK(sw_surface_floater(open, box_id, &got));
    CHECK(got.water_force[1] > 0.0f);
    got.velocity[0] = 2.4f;
    got.drag = 24.0f; /* per second */
    OK(sw_surface_set_floater(open, box_id, &got));
    OK(sw_surface_step(open, 20));
    printf("floaters %016" PRIx64 "\n", floaters_fingerprint(open));
    size_t nodes = 0;
    OK(sw_surface_node_count(open, &nodes));
    float *xyz = malloc(sizeof(float) * 3 * nodes);
    OK(sw_surface_write_positions(open, xyz, 3 * nodes));
    printf("open_positions %016" PRIx64 "\n", fingerprint(xyz, 3 * nodes));
    size_t size = 0;
    uint8_t *snapshot = state_of(open, &size);
    printf("open_snapshot_bytes %zu\n", size);

    /* A snapshot keeps the boundary and the bodies; a copy on the host's job system steps
     * with the same bits. */
    SwSurface *copy = NULL, *hosted = NULL;
    OK(sw_surface_load(snapshot, size, &copy));
    OK(sw_surface_load(snapshot, size, &hosted));
    OK(sw_surface_params(copy, &read_back));
    CHECK(memcmp(&read_back, &params, sizeof params) == 0);
    OK(sw_surface_floater_ids(copy, ids, 4, &count));
    CHECK(count == 2 && ids[0] == ball_id && ids[1] == box_id);
    SwFloater mine = {.struct_size = sizeof mine}, theirs = {.struct_size = sizeof theirs};
    OK(sw_surface_floater(open, box_id, &mine));
    OK(sw_surface_floater(copy, box_id, &theirs));
    CHECK(memcmp(&mine, &theirs, sizeof mine) == 0);
    JobStats stats;
    SwJobSystem jobs = host_jobs(&stats);
    OK(sw_surface_set_job_system(hosted, &jobs));
    OK(sw_surface_step(copy, 25));
    OK(sw_surface_step(hosted, 25));
    size_t copy_size = 0;
    uint8_t *copy_state = state_of(copy, &copy_size);
    CHECK(same_state(hosted, copy_state, copy_size));
    CHECK(atomic_load(&stats.enqueued) >= 2);
    free(copy_state);
    sw_surface_destroy(copy);
    sw_surface_destroy(hosted);

    /* Released on calm water, the bodies settle where buoyancy balances their weight: at rest
       up and down; sideways they still slide slowly down each other's dents (the lattice is a
       membrane: dents attract, as floating cereal does on a cup of milk). */
    OK(sw_surface_step(open, 2500));
    printf("settled %016" PRIx64 "\n", floaters_fingerprint(open));
    OK(sw_surface_buoyancy(open, &buoyancy));
    for (int k = 0; k < 2; k++) {
        OK(sw_surface_floater(open, k == 0 ? ball_id : box_id, &got));
        float speed = sqrtf(got.velocity[0] * got.velocity[0] + got.velocity[1] * got.velocity[1] +
                            got.velocity[2] * got.velocity[2]);
        float weight = got.mass * buoyancy.gravity;
        CHECK(fabsf(got.velocity[1]) < 1e-3f && speed < 0.1f);
        CHECK(fabsf(got.water_force[1] - weight) < 1e-3f * weight);
        CHECK(got.push[0] == 0.0f && got.push[1] == 0.0f && got.push[2] == 0.0f);
    }

    /* Ids are never reused. */
    OK(sw_surface_add_floater(open, &spare, &spare_id));
    CHECK(spare_id == 3);
    OK(sw_surface_remove_floater(open, spare_id));

    /* set_floater: water_force and the other shape's size fields are ignored. */
    SwFloater before_set = {.struct_size = sizeof before_set};
    OK(sw_surface_floater(open, ball_id, &before_set));
    got = before_set;
    got.water_force[1] = NAN;
    got.half_extents[0] = NAN;
    OK(sw_surface_set_floater(open, ball_id, &got));
    OK(sw_surface_floater(open, ball_id, &got));
    CHECK(memcmp(&got, &before_set, sizeof got) == 0);
    /* Pushes add up until the next step; a sum that overflows is refused. */
    OK(sw_surface_push_floater(open, ball_id, FLT_MAX, 0.0f, 0.0f));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_push_floater(open, ball_id, FLT_MAX, 0.0f, 0.0f));
    OK(sw_surface_floater(open, ball_id, &got));
    CHECK(got.push[0] == FLT_MAX);
    OK(sw_surface_set_floater(open, ball_id, &before_set));

    /* ---- Bad input: an error status with a message, and nothing changes. ---- */
    free(snapshot);
    snapshot = state_of(open, &size);
    SwSurface *made_up = (SwSurface *)(uintptr_t)0x7777;
    SwFloaterId id = 99;
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_add_floater(NULL, &ball, &id));
    FAILS(SW_ERROR_INVALID_HANDLE, sw_surface_add_floater(made_up, &ball, &id));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_add_floater(open, NULL, &id));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_add_floater(open, &ball, NULL));
    SwFloater bad = ball;
    bad.shape = 2;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_add_floater(open, &bad, &id));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_floater(open, ball_id, &bad));
    bad.shape = -1;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_add_floater(open, &bad, &id));
    /* Every field out of range, on a sphere and on a box. */
    for (int field = 0; field < 11; field++) {
        bad = field < 2 ? boxy : ball;
        switch (field) {
        case 0: bad.half_extents[1] = -1.0f; break;
        case 1: bad.half_extents[2] = NAN; break;
        case 2: bad.radius = 0.0f; break;
        case 3: bad.radius = 2e9f; break;
        case 4: bad.mass = NAN; break;
        case 5: bad.mass = -1.0f; break;
        case 6: bad.drag = -1.0f; break;
        case 7: bad.position[0] = INFINITY; break;
        case 8: bad.velocity[1] = 2e11f; break;
        case 9: bad.push[2] = NAN; break;
        default: bad.drag = NAN; break;
        }
        FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_add_floater(open, &bad, &id));
        FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_floater(open, box_id, &bad));
    }
    CHECK(id == 99);
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_set_floater(open, box_id, NULL));
    FAILS(SW_ERROR_NO_SUCH_FLOATER, sw_surface_set_floater(open, 12345, &ball));
    FAILS(SW_ERROR_NO_SUCH_FLOATER, sw_surface_floater(open, 12345, &got));
    FAILS(SW_ERROR_NO_SUCH_FLOATER, sw_surface_remove_floater(open, UINT64_MAX));
    FAILS(SW_ERROR_NO_SUCH_FLOATER, sw_surface_push_floater(open, spare_id, 1.0f, 0.0f, 0.0f));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_floater(open, ball_id, NULL));
    FAILS(SW_ERROR_INVALID_HANDLE, sw_surface_floater(made_up, ball_id, &got));
    FAILS(SW_ERROR_INVALID_HANDLE, sw_surface_remove_floater(made_up, ball_id));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_push_floater(NULL, ball_id, 1.0f, 0.0f, 0.0f));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_push_floater(open, ball_id, NAN, 0.0f, 0.0f));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_push_floater(open, ball_id, 0.0f, -INFINITY, 0.0f));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_floater_count(open, NULL));
    FAILS(SW_ERROR_INVALID_HANDLE, sw_surface_floater_count(made_up, &count));
    ids[0] = 7;
    FAILS(SW_ERROR_BUFFER_TOO_SMALL, sw_surface_floater_ids(open, ids, 1, &count));
    CHECK(count == 2 && ids[0] == 7);
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_floater_ids(open, ids, 4, NULL));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_buoyancy(open, NULL));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_set_buoyancy(open, NULL));
    FAILS(SW_ERROR_INVALID_HANDLE, sw_surface_set_buoyancy(made_up, &buoyancy));
    SwBuoyancy bad_buoyancy = sw_buoyancy_default();
    bad_buoyancy.gravity = -1.0f;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_buoyancy(open, &bad_buoyancy));
    bad_buoyancy.gravity = 57.6f;
    bad_buoyancy.density = NAN;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_buoyancy(open, &bad_buoyancy));
    bad_buoyancy.density = 2e6f;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_buoyancy(open, &bad_buoyancy));
    /* A waterline stiff enough to need a smaller timestep. */
    bad_buoyancy.gravity = 57600.0f;
    bad_buoyancy.density = 100.0f;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_buoyancy(open, &bad_buoyancy));
    CHECK(same_state(open, snapshot, size));

    /* Absorbing widths the grid cannot hold, and unknown boundaries. */
    SwSurface *none = NULL;
    SwParams bad_params = params;
    bad_params.absorbing_width = 0;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_create(&bad_params, &none));
    bad_params.absorbing_width = 14; /* 2 * 14 + 2 > 28 rows */
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_create(&bad_params, &none));
    bad_params.absorbing_width = UINT32_MAX;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_create(&bad_params, &none));
    bad_params.absorbing_width = 13; /* the widest that fits */
    OK(sw_surface_create(&bad_params, &again));
    sw_surface_destroy(again);
    bad_params.boundary = 3;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_create(&bad_params, &none));
    bad_params.boundary = -1;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_create(&bad_params, &none));
    /* The width is ignored by the other boundaries. */
    bad_params.boundary = SW_BOUNDARY_FREE;
    bad_params.absorbing_width = 0;
    OK(sw_surface_create(&bad_params, &again));
    OK(sw_surface_params(again, &read_back));
    CHECK(read_back.boundary == SW_BOUNDARY_FREE && read_back.absorbing_width == 32);
    sw_surface_destroy(again);
    CHECK(none == NULL);

    /* A step whose bodies would leave every valid range is refused and changes nothing:
     * a body pushed with the largest float, beside a floating ball and a pending force. */
    SwParams small = sw_params_default();
    small.cols = 32;
    small.rows = 32;
    SwSurface *blow = NULL;
    OK(sw_surface_create(&small, &blow));
    OK(sw_surface_add_force_at(blow, 4.0f, 3.0f, 0.0f, 1.0f, 0.0f));
    SwFloater floating = sw_floater_sphere(2.0f, 5.0f, 16.0f, 0.0f, 16.0f);
    SwFloater thrown = sw_floater_box(1.0f, 0.5f, 1.0f, 1.0f, 8.0f, 0.0f, 8.0f);
    OK(sw_surface_add_floater(blow, &floating, &id));
    OK(sw_surface_add_floater(blow, &thrown, &id));
    OK(sw_surface_push_floater(blow, id, 0.0f, -FLT_MAX, 0.0f));
    SwFloater too_wide = sw_floater_sphere(33.0f, 1.0f, 16.0f, 0.0f, 16.0f);
    SwFloaterId unused = 0;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_add_floater(blow, &too_wide, &unused));
    size_t blow_size = 0;
    uint8_t *blow_state = state_of(blow, &blow_size);
    FAILS(SW_ERROR_NON_FINITE, sw_surface_step(blow, 1));
    char message[512];
    sw_last_error(message, sizeof message);
    CHECK(strstr(message, "floater 1") != NULL);
    FAILS(SW_ERROR_NON_FINITE, sw_surface_advance(blow, 1.0f / 60.0f, NULL));
    CHECK(same_state(blow, blow_state, blow_size));
    free(blow_state);
    sw_surface_destroy(blow);

    /* A destroyed surface's bodies are gone with it. */
    sw_surface_destroy(open);
    FAILS(SW_ERROR_INVALID_HANDLE, sw_surface_floater(open, ball_id, &got));
    FAILS(SW_ERROR_INVALID_HANDLE, sw_surface_push_floater(open, ball_id, 1.0f, 0.0f, 0.0f));
    free(xyz);
    free(snapshot);
}

#endif
