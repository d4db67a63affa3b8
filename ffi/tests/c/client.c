/* A C client of springwater.h, written only from the header: a frame loop over the whole
 * API, a job system on the host's own threads, floating bodies on open water, and every
 * kind of bad input.
 *
 * It prints `key value` lines that tests/c_client.rs compares with the Rust API, and
 * exits non-zero (after printing `FAIL ...`) when a check here fails. */

#include "springwater.h"
#include "check.h"

#include <float.h>
#include <inttypes.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- A job system on the host's own threads (Box2D's enqueueTask / finishTask). ---- */

#define WORKERS 3

typedef struct {
    SwTaskFn task;
    void *task_context;
    uint32_t count;
    atomic_uint next;
    pthread_t threads[WORKERS];
} Job;

typedef struct {
    atomic_uint enqueued;
    atomic_uint items;
} JobStats;

static JobStats *stats_of(void *user_context) { return (JobStats *)user_context; }

static void *worker(void *arg) {
    Job *job = (Job *)arg;
    for (;;) {
        uint32_t i = atomic_fetch_add(&job->next, 1);
        if (i >= job->count) {
            break;
        }
        job->task(i, i + 1, job->task_context);
    }
    return NULL;
}

static void *enqueue_task(SwTaskFn task, uint32_t item_count, uint32_t min_range,
                          void *task_context, void *user_context) {
    (void)min_range;
    JobStats *stats = stats_of(user_context);
    atomic_fetch_add(&stats->enqueued, 1);
    atomic_fetch_add(&stats->items, item_count);
    Job *job = malloc(sizeof *job);
    if (job == NULL) {
        task(0, item_count, task_context); /* ran inline: return NULL */
        return NULL;
    }
    job->task = task;
    job->task_context = task_context;
    job->count = item_count;
    atomic_init(&job->next, 0);
    for (int t = 0; t < WORKERS; t++) {
        pthread_create(&job->threads[t], NULL, worker, job);
    }
    return job;
}

static void finish_task(void *user_task, void *user_context) {
    (void)user_context;
    Job *job = (Job *)user_task;
    for (int t = 0; t < WORKERS; t++) {
        pthread_join(job->threads[t], NULL);
    }
    free(job);
}

/* A broken job system that runs nothing. */
static void *enqueue_nothing(SwTaskFn task, uint32_t item_count, uint32_t min_range,
                             void *task_context, void *user_context) {
    (void)task, (void)item_count, (void)min_range, (void)task_context, (void)user_context;
    return NULL;
}

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
    atomic_init(&stats.enqueued, 0);
    atomic_init(&stats.items, 0);
    SwJobSystem jobs = sw_job_system_default();
    jobs.worker_count = WORKERS;
    jobs.enqueue_task = enqueue_task;
    jobs.finish_task = finish_task;
    jobs.user_context = &stats;
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

/* ---- The frame loop, the same as tests/c_client.rs runs through the Rust API. ---- */

static SwSurface *make_surface(void) {
    SwParams params = sw_params_default();
    params.cols = 48;
    params.rows = 40;
    SwSurface *surface = NULL;
    OK(sw_surface_create(&params, &surface));
    OK(sw_surface_drop_at(surface, 20.0f, 15.0f, 1.0f, 3.0f));
    return surface;
}

static void run_frames(SwSurface *surface, int frames) {
    for (int frame = 0; frame < frames; frame++) {
        if (frame == 10) {
            OK(sw_surface_add_force_at(surface, 10.5f, 12.25f, 0.0f, -2.0f, 0.0f));
        }
        uint32_t substeps = 0;
        OK(sw_surface_advance(surface, 1.0f / 60.0f, &substeps));
        CHECK(substeps == 1);
    }
}

/* ---- Structs that cross carry their size: the makers set it, a wrong one is refused. ---- */

static void struct_sizes(void) {
    SwParams params = sw_params_default();
    SwLodParams lod = sw_lod_params_default();
    SwRefraction view = sw_refraction_default();
    SwFloater ball = sw_floater_sphere(1.0f, 1.0f, 10.0f, 0.5f, 10.0f);
    SwBuoyancy buoyancy = sw_buoyancy_default();
    SwJobSystem jobs = sw_job_system_default();
    CHECK(params.struct_size == sizeof params && lod.struct_size == sizeof lod);
    CHECK(view.struct_size == sizeof view && ball.struct_size == sizeof ball);
    CHECK(buoyancy.struct_size == sizeof buoyancy && jobs.struct_size == sizeof jobs);

    params.cols = 24;
    params.rows = 20;
    SwSurface *surface = NULL;
    OK(sw_surface_create(&params, &surface));
    SwParams unset = params;
    unset.struct_size = 0; /* as if built field by field, without sw_params_default() */
    SwSurface *none = NULL;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_create(&unset, &none));
    CHECK(none == NULL);
    unset.struct_size = sizeof params - 4; /* a header of another version */
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_create(&unset, &none));
    lod.struct_size += 4;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_lod_params(surface, &lod));
    view.struct_size = 0;
    float uv[2 * 24 * 20];
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_write_refraction_uvs(surface, &view, uv, 2 * 24 * 20));
    SwFloaterId id = 0;
    SwFloater bad_ball = ball;
    bad_ball.struct_size = 0;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_add_floater(surface, &bad_ball, &id));
    buoyancy.struct_size = 1;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_buoyancy(surface, &buoyancy));
    jobs.worker_count = 2;
    jobs.enqueue_task = enqueue_task;
    jobs.finish_task = finish_task;
    jobs.struct_size = 0;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_job_system(surface, &jobs));

    /* The deprecated names call the new ones. */
    OK(sw_surface_add_floater(surface, &ball, &id));
    SwSurface *twin = NULL;
    OK(sw_surface_create(&params, &twin));
    OK(sw_surface_add_floater(twin, &ball, &id));
    OK(sw_surface_drop_at(surface, 12.0f, 10.0f, 1.0f, 3.0f));
    OK(sw_surface_drop(twin, 12.0f, 10.0f, 1.0f, 3.0f));
    OK(sw_surface_step(surface, 5));
    OK(sw_surface_step(twin, 5));
    SwFloater a = {.struct_size = sizeof a}, b = {.struct_size = sizeof b};
    OK(sw_surface_floater(surface, id, &a));
    OK(sw_surface_get_floater(twin, id, &b));
    CHECK(a.struct_size == sizeof a && memcmp(&a, &b, sizeof a) == 0);
    sw_surface_destroy(twin);
    sw_surface_destroy(surface);
}

/* ---- The fixed-step clock: 144 Hz frames step every 2.4 frames, the cap drops a stall. ---- */

static void clock_frames(void) {
    SwSurface *surface = make_surface();
    uint32_t taken[3] = {9, 9, 9};
    for (int k = 0; k < 3; k++) {
        OK(sw_surface_advance(surface, 1.0f / 144.0f, &taken[k]));
    }
    CHECK(taken[0] == 0 && taken[1] == 0 && taken[2] == 1);
    float t = -1.0f;
    OK(sw_surface_interpolation(surface, &t));
    CHECK(t > 0.24f && t < 0.26f); /* 3 × 0.4167 − 1 of a step */
    uint32_t steps = 0;
    OK(sw_surface_set_step_cap(surface, 4, 0));
    OK(sw_surface_advance(surface, 1.0f, &steps));
    CHECK(steps == 4);
    OK(sw_surface_set_step_cap(surface, 4, 1));
    OK(sw_surface_advance(surface, 0.1f, &steps)); /* six steps owed, four taken */
    CHECK(steps == 4);
    OK(sw_surface_advance(surface, 0.0f, &steps));
    CHECK(steps == 2);
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_step_cap(surface, 0, 0));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_step_cap(surface, 4, 2));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_interpolation(surface, NULL));
    sw_surface_destroy(surface);
}

/* The moving window: a shift keeps the water at its world place, follow has a dead zone,
   bad input changes nothing. */
static void moving_window(void) {
    SwParams p = sw_params_default();
    p.cols = 40;
    p.rows = 32;
    SwSurface *w = NULL;
    OK(sw_surface_create(&p, &w));
    OK(sw_surface_drop_at(w, 20.0f, 16.0f, 1.0f, 2.0f));
    OK(sw_surface_step(w, 3));
    float before = 0.0f, after = 0.0f, origin[2] = {1.0f, 1.0f};
    OK(sw_surface_origin(w, origin));
    CHECK(origin[0] == 0.0f && origin[1] == 0.0f);
    OK(sw_surface_height_at(w, 21.25f, 15.5f, &before));
    OK(sw_surface_shift(w, 3, -2));
    OK(sw_surface_origin(w, origin));
    CHECK(origin[0] == 3.0f && origin[1] == -2.0f);
    OK(sw_surface_height_at(w, 21.25f, 15.5f, &after));
    CHECK(float_bits(before) == float_bits(after));
    int32_t made[2] = {9, 9};
    OK(sw_surface_follow(w, 23.0f, 13.0f, made)); /* the window's centre: no shift */
    CHECK(made[0] == 0 && made[1] == 0);
    OK(sw_surface_follow(w, 39.9f, 13.0f, made));
    CHECK(made[0] == 17 && made[1] == 0);
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_follow(w, NAN, 0.0f, made));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_follow(w, 90.0f, 0.0f, NULL));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_shift(w, INT32_MAX, 0));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_origin(w, NULL));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_shift(NULL, 1, 0));
    OK(sw_surface_origin(w, origin));
    CHECK(origin[0] == 20.0f && origin[1] == -2.0f);
    /* A floating origin: the frame moves by (20, -2) cells, the water does not. */
    OK(sw_surface_height_at(w, 30.5f, 14.25f, &before));
    OK(sw_surface_rebase(w, 20, -2));
    OK(sw_surface_origin(w, origin));
    CHECK(origin[0] == 0.0f && origin[1] == 0.0f);
    OK(sw_surface_height_at(w, 10.5f, 16.25f, &after));
    CHECK(float_bits(before) == float_bits(after));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_rebase(w, INT64_MIN, 0));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_rebase(NULL, 1, 0));
    OK(sw_surface_origin(w, origin));
    CHECK(origin[0] == 0.0f && origin[1] == 0.0f);
    sw_surface_destroy(w);
}

int main(void) {
    printf("version %s\n", sw_version());
    printf("simd_detect %s\n", sw_simd_level_name(sw_simd_level_detect()));

    SwSurface *water = make_surface();
    size_t nodes = 0;
    OK(sw_surface_node_count(water, &nodes));
    CHECK(nodes == 48 * 40);
    SwParams read_back = {.struct_size = sizeof read_back};
    OK(sw_surface_params(water, &read_back));
    CHECK(read_back.cols == 48 && read_back.rows == 40 && read_back.boundary == SW_BOUNDARY_PINNED);
    SwParams given = sw_params_default();
    given.cols = 48;
    given.rows = 40;
    CHECK(memcmp(&read_back, &given, sizeof given) == 0);

    run_frames(water, 30);

    float *xyz = malloc(sizeof(float) * 3 * nodes);
    float *normals = malloc(sizeof(float) * 3 * nodes);
    float *uv = malloc(sizeof(float) * 2 * nodes);
    SwVertex *vertices = malloc(sizeof(SwVertex) * nodes);
    CHECK(sizeof(SwVertex) == 32);
    OK(sw_surface_write_positions(water, xyz, 3 * nodes));
    printf("positions %016" PRIx64 "\n", fingerprint(xyz, 3 * nodes));

    SwRefraction refraction = sw_refraction_default();
    refraction.eye_x = 24.0f;
    refraction.eye_y = 30.0f;
    refraction.eye_z = -20.0f;
    OK(sw_surface_write_normals(water, normals, 3 * nodes));
    OK(sw_surface_write_refraction_uvs(water, &refraction, uv, 2 * nodes));
    OK(sw_surface_write_vertices(water, &refraction, vertices, nodes));
    printf("normals %016" PRIx64 "\n", fingerprint(normals, 3 * nodes));
    printf("uvs %016" PRIx64 "\n", fingerprint(uv, 2 * nodes));
    /* The packed vertices hold the same bits as the separate buffers. */
    for (size_t i = 0; i < nodes; i++) {
        CHECK(memcmp(vertices[i].position, &xyz[3 * i], 12) == 0);
        CHECK(memcmp(vertices[i].normal, &normals[3 * i], 12) == 0);
        CHECK(memcmp(vertices[i].uv, &uv[2 * i], 8) == 0);
    }

    /* Queries, single and batched. */
    float height = 0.0f, normal[3], velocity[3];
    OK(sw_surface_height_at(water, 20.5f, 15.25f, &height));
    OK(sw_surface_normal_at(water, 20.5f, 15.25f, normal));
    OK(sw_surface_velocity_at(water, 20.5f, 15.25f, velocity));
    printf("height %08" PRIx32 "\n", float_bits(height));
    printf("normal %08" PRIx32 " %08" PRIx32 " %08" PRIx32 "\n", float_bits(normal[0]),
           float_bits(normal[1]), float_bits(normal[2]));
    printf("velocity %08" PRIx32 "\n", float_bits(velocity[1]));
    float points[6] = {20.5f, 15.25f, 0.0f, 0.0f, 47.0f, 39.0f};
    SwSample samples[3];
    OK(sw_surface_sample(water, points, 3, samples, 3));
    CHECK(float_bits(samples[0].height) == float_bits(height));
    CHECK(memcmp(samples[0].normal, normal, 12) == 0);
    CHECK(memcmp(samples[0].velocity, velocity, 12) == 0);

    /* The LOD index buffer: ask its size, fill it, update again from the same eye. */
    SwBool changed = 0;
    size_t count = 0;
    OK(sw_surface_lod_indices(water, NULL, 0, &count));
    CHECK(count == 0);
    SwLodParams lod = sw_lod_params_default();
    lod.patch_cells = 8;
    lod.levels = 3;
    lod.first_range = 12.0f;
    OK(sw_surface_set_lod_params(water, &lod));
    OK(sw_surface_update_lod(water, 0.0f, 10.0f, 0.0f, &changed));
    CHECK(changed == 1);
    OK(sw_surface_lod_indices(water, NULL, 0, &count));
    CHECK(count > 0 && count % 3 == 0);
    uint32_t *indices = malloc(sizeof(uint32_t) * count);
    size_t written = 0;
    OK(sw_surface_lod_indices(water, indices, count, &written));
    CHECK(written == count);
    for (size_t i = 0; i < count; i++) {
        CHECK(indices[i] < nodes);
    }
    OK(sw_surface_update_lod(water, 0.0f, 10.0f, 0.0f, &changed));
    CHECK(changed == 0);
    printf("lod_indices %zu\n", count);

    /* Energy and SIMD level. */
    SwEnergy energy;
    OK(sw_surface_energy(water, &energy));
    CHECK(energy.total > 0.0 && energy.total == energy.kinetic + energy.potential);
    SwSimdLevel level = -1;
    OK(sw_surface_simd_level(water, &level));
    printf("simd %s\n", sw_simd_level_name(level));

    /* Snapshots: ask the size, save, load into a second surface; both continue alike. */
    size_t size = 0;
    OK(sw_surface_save(water, NULL, 0, &size));
    uint8_t *snapshot = malloc(size);
    OK(sw_surface_save(water, snapshot, size, &size));
    printf("snapshot_bytes %zu\n", size);
    SwSurface *copy = NULL;
    OK(sw_surface_load(snapshot, size, &copy));
    OK(sw_surface_step(water, 17));
    OK(sw_surface_step(copy, 17));
    float *xyz_copy = malloc(sizeof(float) * 3 * nodes);
    OK(sw_surface_write_positions(water, xyz, 3 * nodes));
    OK(sw_surface_write_positions(copy, xyz_copy, 3 * nodes));
    CHECK(memcmp(xyz, xyz_copy, sizeof(float) * 3 * nodes) == 0);
    OK(sw_surface_restore(copy, snapshot, size));

    /* Rollback: save every frame into one buffer; go back 3 frames, step them again with
       the same inputs, and the hashes equal the straight run's, frame by frame. */
    uint8_t *frames[6];
    uint64_t straight[6], again = 0;
    for (int f = 0; f < 6; ++f) {
        frames[f] = malloc(size);
        OK(sw_surface_save(copy, frames[f], size, &size));
        OK(sw_surface_drop_at(copy, 4.0f + f, 5.0f, 0.25f, 2.0f));
        OK(sw_surface_advance(copy, 1.0f / 60.0f, NULL));
        OK(sw_surface_state_hash(copy, &straight[f]));
    }
    CHECK(straight[4] != straight[5]);
    OK(sw_surface_restore(copy, frames[3], size));
    for (int f = 3; f < 6; ++f) {
        OK(sw_surface_drop_at(copy, 4.0f + f, 5.0f, 0.25f, 2.0f));
        OK(sw_surface_advance(copy, 1.0f / 60.0f, NULL));
        OK(sw_surface_state_hash(copy, &again));
        CHECK(again == straight[f]);
    }
    printf("rollback_hash %016llx\n", (unsigned long long)again);
    for (int f = 0; f < 6; ++f) free(frames[f]);
    OK(sw_surface_restore(copy, snapshot, size));

    /* The host's job system: the same bits as the built-in pool, on its own threads. */
    JobStats stats;
    atomic_init(&stats.enqueued, 0);
    atomic_init(&stats.items, 0);
    SwJobSystem jobs = sw_job_system_default();
    jobs.worker_count = WORKERS;
    jobs.enqueue_task = enqueue_task;
    jobs.finish_task = finish_task;
    jobs.user_context = &stats;
    SwSurface *hosted = NULL;
    OK(sw_surface_load(snapshot, size, &hosted));
    OK(sw_surface_set_job_system(hosted, &jobs));
    OK(sw_surface_step(hosted, 17));
    OK(sw_surface_write_positions(hosted, xyz_copy, 3 * nodes));
    CHECK(memcmp(xyz, xyz_copy, sizeof(float) * 3 * nodes) == 0);
    CHECK(atomic_load(&stats.enqueued) >= 2);
    printf("job_batches %u\n", atomic_load(&stats.enqueued));

    /* ---- Bad input: an error status with a message, and nothing changes. ---- */
    OK(sw_surface_write_positions(water, xyz, 3 * nodes));
    uint64_t before = fingerprint(xyz, 3 * nodes);
    SwParams bad = sw_params_default();
    SwSurface *none = NULL;
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_create(NULL, &none));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_create(&bad, NULL));
    bad.cols = 1;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_create(&bad, &none));
    bad = sw_params_default();
    bad.dt = NAN;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_create(&bad, &none));
    bad = sw_params_default();
    bad.dt = 0.5f; /* past the critical timestep */
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_create(&bad, &none));
    bad = sw_params_default();
    bad.boundary = 7;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_create(&bad, &none));
    bad = sw_params_default();
    bad.boundary = SW_BOUNDARY_ABSORBING;
    bad.absorbing_width = 0;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_create(&bad, &none));
    bad = sw_params_default();
    bad.cols = 100000;
    bad.rows = 100000;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_create(&bad, &none));
    CHECK(none == NULL);

    FAILS(SW_ERROR_NULL_POINTER, sw_surface_advance(NULL, 0.016f, NULL));
    FAILS(SW_ERROR_INVALID_HANDLE, sw_surface_advance((SwSurface *)(uintptr_t)0x7777, 0.016f, NULL));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_advance(water, NAN, NULL));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_advance(water, -1.0f, NULL));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_drop_at(water, 20.0f, 15.0f, NAN, 3.0f));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_drop_at(water, 20.0f, 15.0f, 1.0f, 0.0f));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_add_force_at(water, 10.0f, 10.0f, 0.0f, INFINITY, 0.0f));
    FAILS(SW_ERROR_OUTSIDE_GRID, sw_surface_add_force_at(water, -1.0f, 10.0f, 0.0f, 1.0f, 0.0f));
    FAILS(SW_ERROR_OUTSIDE_GRID, sw_surface_height_at(water, 100.0f, 0.0f, &height));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_height_at(water, NAN, 0.0f, &height));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_height_at(water, 1.0f, 1.0f, NULL));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_normal_at(water, 1.0f, 1.0f, NULL));
    points[2] = -5.0f;
    SwSample untouched[3] = {{0}};
    FAILS(SW_ERROR_OUTSIDE_GRID, sw_surface_sample(water, points, 3, untouched, 3));
    CHECK(untouched[0].height == 0.0f);
    FAILS(SW_ERROR_BUFFER_TOO_SMALL, sw_surface_sample(water, points, 3, samples, 2));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_sample(water, NULL, 3, samples, 3));
    /* Point by point: the point off the water is marked, the others answered. */
    SwSample each[3];
    uint8_t found[3] = {7, 7, 7};
    float here = 0.0f, up[3];
    OK(sw_surface_height_at(water, points[0], points[1], &here));
    OK(sw_surface_normal_at(water, points[0], points[1], up));
    OK(sw_surface_sample_each(water, points, 3, each, 3, found, 3));
    CHECK(found[0] == 1 && found[1] == 0 && found[2] == 1);
    CHECK(float_bits(each[0].height) == float_bits(here));
    CHECK(memcmp(each[0].normal, up, 12) == 0);
    CHECK(each[1].height == 0.0f && each[1].normal[1] == 1.0f);
    FAILS(SW_ERROR_BUFFER_TOO_SMALL, sw_surface_sample_each(water, points, 3, each, 3, found, 2));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_sample_each(water, points, 3, each, 3, NULL, 3));
    FAILS(SW_ERROR_BUFFER_TOO_SMALL, sw_surface_write_positions(water, xyz, 3 * nodes - 1));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_write_positions(water, NULL, 3 * nodes));
    FAILS(SW_ERROR_BUFFER_TOO_SMALL, sw_surface_write_normals(water, normals, 5));
    FAILS(SW_ERROR_BUFFER_TOO_SMALL, sw_surface_write_refraction_uvs(water, &refraction, uv, 2 * nodes - 2));
    FAILS(SW_ERROR_BUFFER_TOO_SMALL, sw_surface_write_vertices(water, &refraction, vertices, nodes - 1));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_write_vertices(water, NULL, vertices, nodes));
    SwRefraction bad_refraction = refraction;
    bad_refraction.eye_y = NAN;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_write_vertices(water, &bad_refraction, vertices, nodes));
    bad_refraction = refraction;
    bad_refraction.ior = 0.5f;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_write_refraction_uvs(water, &bad_refraction, uv, 2 * nodes));
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_update_lod(water, INFINITY, 1.0f, 1.0f, &changed));
    SwLodParams bad_lod = sw_lod_params_default();
    bad_lod.patch_cells = 12;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_lod_params(water, &bad_lod));
    FAILS(SW_ERROR_BUFFER_TOO_SMALL, sw_surface_lod_indices(water, indices, count - 1, &written));
    CHECK(written == count);
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_lod_indices(water, indices, count, NULL));
    FAILS(SW_ERROR_BUFFER_TOO_SMALL, sw_surface_save(water, snapshot, size - 1, &written));
    CHECK(written == size);
    snapshot[size / 2] ^= 0x40;
    FAILS(SW_ERROR_SNAPSHOT, sw_surface_restore(water, snapshot, size));
    FAILS(SW_ERROR_SNAPSHOT, sw_surface_load(snapshot, size, &none));
    FAILS(SW_ERROR_SNAPSHOT, sw_surface_load(snapshot, 10, &none));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_load(NULL, size, &none));
    CHECK(none == NULL);
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_simd_level(water, 9, NULL));
    SwJobSystem bad_jobs = sw_job_system_default();
    bad_jobs.worker_count = 0;
    bad_jobs.enqueue_task = enqueue_task;
    bad_jobs.finish_task = finish_task;
    bad_jobs.user_context = &stats;
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_set_job_system(water, &bad_jobs));
    bad_jobs.worker_count = 2;
    bad_jobs.finish_task = NULL;
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_set_job_system(water, &bad_jobs));
    FAILS(SW_ERROR_NULL_POINTER, sw_surface_energy(water, NULL));

    /* A job system that runs nothing fails the step and changes nothing. */
    SwJobSystem lazy = bad_jobs;
    lazy.worker_count = 2;
    lazy.enqueue_task = enqueue_nothing;
    lazy.finish_task = finish_task;
    OK(sw_surface_set_job_system(water, &lazy));
    FAILS(SW_ERROR_JOB_SYSTEM, sw_surface_step(water, 4));
    FAILS(SW_ERROR_JOB_SYSTEM, sw_surface_advance(water, 0.1f, NULL));
    OK(sw_surface_set_job_system(water, NULL));

    OK(sw_surface_write_positions(water, xyz, 3 * nodes));
    CHECK(fingerprint(xyz, 3 * nodes) == before);

    /* sw_last_error: the size it needs, and a message cut to a small buffer. */
    FAILS(SW_ERROR_INVALID_ARGUMENT, sw_surface_advance(water, NAN, NULL));
    char tiny[8];
    size_t needed = sw_last_error(tiny, sizeof tiny);
    CHECK(needed > sizeof tiny && strlen(tiny) == sizeof tiny - 1);
    CHECK(sw_last_error(NULL, 0) == needed);

    /* A destroyed handle is refused; its neighbours go on working. */
    sw_surface_destroy(copy);
    FAILS(SW_ERROR_INVALID_HANDLE, sw_surface_step(copy, 1));
    FAILS(SW_ERROR_INVALID_HANDLE, sw_surface_write_positions(copy, xyz, 3 * nodes));
    sw_surface_destroy(copy); /* twice: a no-op */
    sw_surface_destroy(NULL);
    OK(sw_surface_step(water, 1));
    OK(sw_surface_step(hosted, 1));

    sw_surface_destroy(hosted);
    sw_surface_destroy(water);
    floating_bodies();
    clock_frames();
    struct_sizes();
    moving_window();
    free(xyz);
    free(xyz_copy);
    free(normals);
    free(uv);
    free(vertices);
    free(indices);
    free(snapshot);

    printf("checks %s\n", failures == 0 ? "passed" : "FAILED");
    return failures == 0 ? 0 : 1;
}
