/*
 * fuzz.h - what every libFuzzer harness of tests/fuzz/ shares: a reader
 * that takes typed values off the fuzzer's bytes (zeros once they run out,
 * so every input means something and a shorter input is a simpler one),
 * the check that turns a broken property into a crash libFuzzer records,
 * and the sanitizers' options.  Include it from the one .c of a target.
 */
#ifndef TESTS_FUZZ_H
#define TESTS_FUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* UBSan reports are recoverable by default and would only be printed: make
 * each one fatal, so that libFuzzer keeps the input.  tools/make/fuzz.mk
 * adds the suppressions of known defects (tests/fuzz/known_defects.supp)
 * through UBSAN_OPTIONS, which is read after these. */
const char *__ubsan_default_options(void);
const char *__ubsan_default_options(void)
{
    return "halt_on_error=1:print_stacktrace=1:report_error_type=1";
}

/** A property of the code under test does not hold: say which, and abort
 *  (libFuzzer saves the input as crash-<sha1>). */
#define FUZZ_CHECK(cond)                                                                 \
    do {                                                                                 \
        if (!(cond)) {                                                                   \
            fprintf(stderr, "%s:%d: property failed: %s\n", __FILE__, __LINE__, #cond); \
            abort();                                                                     \
        }                                                                                \
    } while (0)

typedef struct fuzz_in {
    const uint8_t *p;
    size_t left;
} fuzz_in_t;

static inline fuzz_in_t fuzz_in(const uint8_t *data, size_t size)
{
    fuzz_in_t in = { data, size };
    return in;
}

static inline uint8_t fuzz_u8(fuzz_in_t *in)
{
    if (in->left == 0) {
        return 0;
    }
    in->left--;
    return *in->p++;
}

/** Big-endian, as the project's frames are. */
static inline uint16_t fuzz_u16(fuzz_in_t *in)
{
    uint16_t hi = fuzz_u8(in);
    return (uint16_t)((hi << 8) | fuzz_u8(in));
}

static inline uint32_t fuzz_u32(fuzz_in_t *in)
{
    uint32_t hi = fuzz_u16(in);
    return (hi << 16) | fuzz_u16(in);
}

/** A float from 4 raw bytes: NaNs, infinities and denormals included. */
static inline float fuzz_f32_bits(fuzz_in_t *in)
{
    uint32_t u = fuzz_u32(in);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/** Up to `n` bytes into `out`; returns how many there were. */
static inline size_t fuzz_bytes(fuzz_in_t *in, uint8_t *out, size_t n)
{
    size_t k = n < in->left ? n : in->left;
    memcpy(out, in->p, k);
    in->p += k;
    in->left -= k;
    return k;
}

#endif
