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

/* The host's job system: WORKERS threads of this client's own, counting into `stats`. */
static SwJobSystem host_jobs(JobStats *stats) {
    atomic_init(&stats->enqueued, 0);
    atomic_init(&stats->items, 0);
    SwJobSystem jobs = sw_job_system_default();
    jobs.worker_count = WORKERS;
    jobs.enqueue_task = enqueue_task;
    jobs.finish_task = finish_task;
    jobs.user_context = stats;
    return jobs;
}

#include "client_floaters.h"

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
    SwJobSystem jobs = host_jobs(&stats);
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
