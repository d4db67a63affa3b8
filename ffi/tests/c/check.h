/* What the C clients of springwater.h share: checks that count failures and print them,
 * and the bits of floats for the values they print. For single-file test programs: include
 * it once, after springwater.h. */

#ifndef SPRINGWATER_TEST_CHECK_H
#define SPRINGWATER_TEST_CHECK_H

#include <stdint.h>
#include <stdio.h>
#include <string.h>

static int failures = 0;

#define CHECK(cond)                                                                     \
    do {                                                                                \
        if (!(cond)) {                                                                  \
            printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond);                      \
            failures++;                                                                 \
        }                                                                               \
    } while (0)

/* A call that must succeed. */
#define OK(call)                                                                        \
    do {                                                                                \
        SwStatus status_ = (call);                                                      \
        if (status_ != SW_OK) {                                                         \
            char message_[512];                                                         \
            sw_last_error(message_, sizeof message_);                                   \
            printf("FAIL %s:%d: %s returned %s: %s\n", __FILE__, __LINE__, #call,        \
                   sw_status_name(status_), message_);                                  \
            failures++;                                                                 \
        }                                                                               \
    } while (0)

/* A call that must fail with `expected` and leave a message. */
#define FAILS(expected, call)                                                           \
    do {                                                                                \
        SwStatus status_ = (call);                                                      \
        char message_[512] = "";                                                        \
        size_t needed_ = sw_last_error(message_, sizeof message_);                      \
        if (status_ != (expected) || needed_ < 2 || message_[0] == 0) {                 \
            printf("FAIL %s:%d: %s returned %s, expected %s (message: '%s')\n",         \
                   __FILE__, __LINE__, #call, sw_status_name(status_),                  \
                   sw_status_name(expected), message_);                                 \
            failures++;                                                                 \
        }                                                                               \
    } while (0)

/* FNV-1a over the bits of `n` floats. */
static inline uint64_t fingerprint(const float *v, size_t n) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < n; i++) {
        uint32_t bits;
        memcpy(&bits, &v[i], 4);
        for (int b = 0; b < 4; b++) {
            h ^= (bits >> (8 * b)) & 0xff;
            h *= 0x100000001b3ull;
        }
    }
    return h;
}

static inline uint32_t float_bits(float f) {
    uint32_t bits;
    memcpy(&bits, &f, 4);
    return bits;
}

#endif
