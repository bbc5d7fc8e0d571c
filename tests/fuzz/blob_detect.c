/*
 * blob_detect.c - fuzz target: hal/blob_detect.c, the robot's colour blob
 * detector, against tests/blob_detect_old.h, a copy of the detector as it
 * was before the lookup tables and the 16-bit per-blob arithmetic.  Any
 * frame and parameters must give the same count and the same blobs in the
 * same order (and never more than asked or than BLOB_DETECT_MAX_BLOBS).
 *
 * Input (fuzz.h's reader: zeros once the bytes run out):
 *   u8  flags: bit 0 byte order; bit 1 thresholds from the input (else the
 *       defaults: the table path the robot runs); bit 2 field of view from
 *       the input (else 977 mrad); bit 3 raw sizes, field of view and byte
 *       order, so that out-of-range values (rejected) occur too
 *   u8  width, u8 height   1 + value % 160 (raw: 0..255)
 *   u16 fov_mrad           1 + value % 6283 (raw: as is)
 *   u8  min_column_pixels  value % 8
 *   u16 min_pixels         as is
 *   u8  max                value % (BLOB_DETECT_MAX_BLOBS + 2)
 *   u8 x 3                 min_value, min_margin, min_saturation_q8 (bit 1)
 *   the frame's bytes      repeated to fill width x height pixels (none:
 *                          all zero), so that a short input is a
 *                          structured frame
 * The seeds (tests/fuzz/corpus/blob_detect/) are the CPU report's frame, a
 * 120 x 1 line, stripes under other thresholds, and the largest frame.
 */
#include "fuzz.h"

#include "blob_detect.h"
#include "blob_detect_old.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static uint8_t frame[2u * BLOB_MAX_WIDTH * BLOB_MAX_HEIGHT];
    fuzz_in_t in = fuzz_in(data, size);
    blob_detect_params_t p = blob_detect_default_params();
    blob_detect_work_t w_new, w_old;
    hal_blob_t out_new[BLOB_DETECT_MAX_BLOBS], out_old[BLOB_DETECT_MAX_BLOBS];
    uint8_t flags = fuzz_u8(&in);
    uint8_t wb = fuzz_u8(&in), hb = fuzz_u8(&in);
    uint16_t fov = fuzz_u16(&in);
    uint16_t width, height;
    uint8_t max, n_new, n_old;
    size_t need, got;

    if (flags & 8u) {
        width = wb;
        height = hb;
        p.fov_mrad = fov;
        p.byte_order = (uint8_t)(flags & 1u) | (uint8_t)((flags >> 3) & 2u);
    } else {
        width = (uint16_t)(1u + wb % BLOB_MAX_WIDTH);
        height = (uint16_t)(1u + hb % BLOB_MAX_HEIGHT);
        if (flags & 4u) {
            p.fov_mrad = (uint16_t)(1u + fov % BLOB_MAX_FOV_MRAD);
        }
        p.byte_order = (uint8_t)(flags & 1u);
    }
    p.min_column_pixels = (uint16_t)(fuzz_u8(&in) % 8u);
    p.min_pixels = fuzz_u16(&in);
    max = (uint8_t)(fuzz_u8(&in) % (BLOB_DETECT_MAX_BLOBS + 2u));
    if (flags & 2u) {
        p.min_value = fuzz_u8(&in);
        p.min_margin = fuzz_u8(&in);
        p.min_saturation_q8 = fuzz_u8(&in);
    }

    need = 2u * (size_t)(width > BLOB_MAX_WIDTH ? BLOB_MAX_WIDTH : width) *
           (height > BLOB_MAX_HEIGHT ? BLOB_MAX_HEIGHT : height);
    got = fuzz_bytes(&in, frame, need);
    if (got == 0u) {
        memset(frame, 0, need);
    } else {
        for (size_t i = got; i < need; i++) {
            frame[i] = frame[i - got];
        }
    }

    memset(&w_new, 0x5A, sizeof w_new);
    memset(&w_old, 0xA5, sizeof w_old);
    n_new = blob_detect(&p, frame, width, height, &w_new, out_new, max);
    n_old = old_blob_detect(&p, frame, width, height, &w_old, out_old, max);
    FUZZ_CHECK(n_new == n_old);
    FUZZ_CHECK(n_new <= max && n_new <= BLOB_DETECT_MAX_BLOBS);
    for (uint8_t i = 0; i < n_new; i++) {
        FUZZ_CHECK(out_new[i].colour == out_old[i].colour);
        FUZZ_CHECK(out_new[i].pixels == out_old[i].pixels);
        FUZZ_CHECK(out_new[i].bearing_mrad == out_old[i].bearing_mrad);
        FUZZ_CHECK(out_new[i].width_mrad == out_old[i].width_mrad);
    }
    return 0;
}
