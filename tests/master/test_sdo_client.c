/*
 * test_sdo_client.c - the SDO client channel (runtime/odg_sdo_client.c) against a scripted
 * server: every request the client sends is checked byte for byte, and the answers are the
 * ones CiA 301 gives (or wrong ones, to see the client abort).
 */
#include <string.h>

#include "check.h"
#include "odg_sdo_client.h"

static odg_frame_t sent[16];
static unsigned n_sent;
static int fail_send;

static int fake_send(void *ctx, const odg_frame_t *f)
{
    (void)ctx;
    if (fail_send) {
        return -1;
    }
    if (n_sent < 16u) {
        sent[n_sent] = *f;
    }
    n_sent++;
    return 0;
}

/* The last frame the client sent, as 8 bytes. */
static const uint8_t *last(void)
{
    return sent[n_sent - 1u].data;
}

static int answer(odg_sdoc_t *ch, uint32_t id, const uint8_t d[8])
{
    odg_frame_t f;
    f.id = id;
    f.len = 8;
    f.flags = 0;
    memcpy(f.data, d, 8);
    return odg_sdoc_receive(ch, &f);
}

static void test_expedited_download(void)
{
    odg_sdoc_t ch;
    const uint8_t value[2] = {0x64, 0x00};
    const uint8_t ok[8] = {0x60, 0x17, 0x10, 0x00, 0, 0, 0, 0};
    const uint8_t req[8] = {0x2B, 0x17, 0x10, 0x00, 0x64, 0x00, 0, 0};
    n_sent = 0;
    odg_sdoc_init(&ch, 5, 0, 0, fake_send, NULL);
    CHECK_EQ(odg_sdoc_download(&ch, 0x1017, 0, value, 2), ODG_OK);
    CHECK_EQ(n_sent, 1);
    CHECK_EQ(sent[0].id, 0x605);
    CHECK(memcmp(last(), req, 8) == 0);
    CHECK_EQ(odg_sdoc_download(&ch, 0x1017, 0, value, 2), ODG_ABORT_DATA_STATE); /* one at a time */
    CHECK_EQ(answer(&ch, 0x586, ok), 0); /* another server's answer is not taken */
    CHECK_EQ(ch.state, ODG_SDOC_BUSY);
    CHECK_EQ(answer(&ch, 0x585, ok), 1);
    CHECK_EQ(ch.state, ODG_SDOC_DONE);
    CHECK_EQ(answer(&ch, 0x585, ok), 1); /* a late duplicate changes nothing */
    CHECK_EQ(ch.state, ODG_SDOC_DONE);
    CHECK_EQ(n_sent, 1);
}

static void test_segmented_download(void)
{
    odg_sdoc_t ch;
    uint8_t value[10];
    uint8_t d[8] = {0x60, 0x00, 0x20, 0x01, 0, 0, 0, 0};
    unsigned i;
    for (i = 0; i < 10u; i++) {
        value[i] = (uint8_t)(0xA0u + i);
    }
    n_sent = 0;
    odg_sdoc_init(&ch, 5, 0x640, 0x5C0, fake_send, NULL); /* COB-IDs of a client parameter */
    CHECK_EQ(odg_sdoc_download(&ch, 0x2000, 1, value, 10), ODG_OK);
    CHECK_EQ(sent[0].id, 0x640);
    CHECK_EQ(last()[0], 0x21); /* size indicated */
    CHECK_EQ(odg_sdoc_u32(last() + 4, 4), 10);
    CHECK_EQ(answer(&ch, 0x5C0, d), 1);
    CHECK_EQ(n_sent, 2);
    CHECK_EQ(last()[0], 0x00); /* toggle 0, 7 bytes, more to come */
    CHECK(memcmp(last() + 1, value, 7) == 0);
    d[0] = 0x20;
    CHECK_EQ(answer(&ch, 0x5C0, d), 1);
    CHECK_EQ(n_sent, 3);
    CHECK_EQ(last()[0], 0x10 | (4u << 1) | 1u); /* toggle 1, 3 bytes (4 unused), last */
    CHECK(memcmp(last() + 1, value + 7, 3) == 0);
    CHECK_EQ(ch.state, ODG_SDOC_BUSY);
    d[0] = 0x20; /* the toggle of the segment before: the client aborts */
    CHECK_EQ(answer(&ch, 0x5C0, d), 1);
    CHECK_EQ(ch.state, ODG_SDOC_ABORTED);
    CHECK_EQ(ch.abort, ODG_ABORT_TOGGLE);
    CHECK_EQ(last()[0], 0x80);
    CHECK_EQ(odg_sdoc_u32(last() + 4, 4), ODG_ABORT_TOGGLE);
    /* the same again, answered right */
    n_sent = 0;
    CHECK_EQ(odg_sdoc_download(&ch, 0x2000, 1, value, 10), ODG_OK);
    d[0] = 0x60;
    (void)answer(&ch, 0x5C0, d);
    d[0] = 0x20;
    (void)answer(&ch, 0x5C0, d);
    d[0] = 0x30;
    (void)answer(&ch, 0x5C0, d);
    CHECK_EQ(ch.state, ODG_SDOC_DONE);
    CHECK_EQ(n_sent, 3);
}

static void test_empty_download(void)
{
    odg_sdoc_t ch;
    uint8_t d[8] = {0x60, 0x00, 0x20, 0x01, 0, 0, 0, 0};
    n_sent = 0;
    odg_sdoc_init(&ch, 5, 0, 0, fake_send, NULL);
    CHECK_EQ(odg_sdoc_download(&ch, 0x2000, 1, NULL, 0), ODG_OK);
    CHECK_EQ(last()[0], 0x21);
    CHECK_EQ(odg_sdoc_u32(last() + 4, 4), 0);
    (void)answer(&ch, 0x585, d);
    CHECK_EQ(last()[0], (7u << 1) | 1u); /* one empty last segment */
    d[0] = 0x20;
    (void)answer(&ch, 0x585, d);
    CHECK_EQ(ch.state, ODG_SDOC_DONE);
}

static void test_uploads(void)
{
    odg_sdoc_t ch;
    uint8_t buf[16];
    const uint8_t exp[8] = {0x43, 0x00, 0x10, 0x00, 0x91, 0x01, 0x0E, 0x00};
    const uint8_t exp2[8] = {0x4F, 0x01, 0x10, 0x00, 0x2A, 0, 0, 0};
    uint8_t seg[8] = {0x41, 0x08, 0x10, 0x00, 9, 0, 0, 0};
    n_sent = 0;
    odg_sdoc_init(&ch, 7, 0, 0, fake_send, NULL);
    CHECK_EQ(odg_sdoc_upload(&ch, 0x1000, 0, buf, sizeof buf), ODG_OK);
    CHECK_EQ(last()[0], 0x40);
    CHECK_EQ(sent[0].id, 0x607);
    (void)answer(&ch, 0x587, exp);
    CHECK_EQ(ch.state, ODG_SDOC_DONE);
    CHECK_EQ(ch.n, 4);
    CHECK_EQ(odg_sdoc_u32(buf, ch.n), 0x000E0191);
    CHECK_EQ(odg_sdoc_upload(&ch, 0x1001, 0, buf, sizeof buf), ODG_OK);
    (void)answer(&ch, 0x587, exp2); /* expedited, 1 byte */
    CHECK_EQ(ch.n, 1);
    CHECK_EQ(buf[0], 0x2A);
    /* segmented: 9 bytes in two segments */
    n_sent = 0;
    CHECK_EQ(odg_sdoc_upload(&ch, 0x1008, 0, buf, sizeof buf), ODG_OK);
    (void)answer(&ch, 0x587, seg);
    CHECK_EQ(last()[0], 0x60);
    memcpy(seg, "\x00" "abcdefg", 8);
    (void)answer(&ch, 0x587, seg);
    CHECK_EQ(last()[0], 0x70);
    memcpy(seg, "\x1B" "hi\0\0\0\0\0", 8); /* toggle 1, 5 unused, last */
    (void)answer(&ch, 0x587, seg);
    CHECK_EQ(ch.state, ODG_SDOC_DONE);
    CHECK_EQ(ch.n, 9);
    CHECK(memcmp(buf, "abcdefghi", 9) == 0);
    /* a value longer than the buffer is refused at the start */
    n_sent = 0;
    CHECK_EQ(odg_sdoc_upload(&ch, 0x1008, 0, buf, 4), ODG_OK);
    seg[0] = 0x41;
    seg[1] = 0x08;
    seg[2] = 0x10;
    seg[3] = 0;
    seg[4] = 9;
    seg[5] = seg[6] = seg[7] = 0;
    (void)answer(&ch, 0x587, seg);
    CHECK_EQ(ch.state, ODG_SDOC_ABORTED);
    CHECK_EQ(ch.abort, ODG_ABORT_OUT_OF_MEMORY);
    CHECK_EQ(last()[0], 0x80);
    /* an answer or abort about another object (late, of a transfer given up) is ignored */
    n_sent = 0;
    CHECK_EQ(odg_sdoc_upload(&ch, 0x1000, 0, buf, sizeof buf), ODG_OK);
    CHECK_EQ(answer(&ch, 0x587, exp2), 1);
    seg[0] = 0x80;
    seg[1] = 0x08;
    seg[2] = 0x10;
    CHECK_EQ(answer(&ch, 0x587, seg), 1);
    CHECK_EQ(ch.state, ODG_SDOC_BUSY);
    CHECK_EQ(n_sent, 1);
    (void)answer(&ch, 0x587, exp);
    CHECK_EQ(ch.state, ODG_SDOC_DONE);
    CHECK_EQ(odg_sdoc_u32(buf, ch.n), 0x000E0191);
    /* an upload segment while an initiate answer is awaited: aborted */
    CHECK_EQ(odg_sdoc_upload(&ch, 0x1000, 0, buf, sizeof buf), ODG_OK);
    memcpy(seg, "\x00" "abcdefg", 8);
    (void)answer(&ch, 0x587, seg);
    CHECK_EQ(ch.abort, ODG_ABORT_COMMAND);
}

static void test_server_abort_and_timeout(void)
{
    odg_sdoc_t ch;
    uint8_t buf[4];
    const uint8_t abort[8] = {0x80, 0x00, 0x30, 0x00, 0x00, 0x00, 0x02, 0x06};
    n_sent = 0;
    odg_sdoc_init(&ch, 3, 0, 0, fake_send, NULL);
    CHECK_EQ(odg_sdoc_upload(&ch, 0x3000, 0, buf, sizeof buf), ODG_OK);
    (void)answer(&ch, 0x583, abort);
    CHECK_EQ(ch.state, ODG_SDOC_ABORTED);
    CHECK_EQ(ch.abort, ODG_ABORT_NO_OBJECT);
    CHECK_EQ(n_sent, 1); /* an abort is not answered */
    CHECK_EQ(odg_sdoc_upload(&ch, 0x1000, 0, buf, sizeof buf), ODG_OK);
    odg_sdoc_tick(&ch, ODG_SDOC_TIMEOUT_MS - 1u);
    CHECK_EQ(ch.state, ODG_SDOC_BUSY);
    odg_sdoc_tick(&ch, 1);
    CHECK_EQ(ch.state, ODG_SDOC_ABORTED);
    CHECK_EQ(ch.abort, ODG_ABORT_TIMEOUT);
    CHECK_EQ(last()[0], 0x80);
    CHECK_EQ(odg_sdoc_u32(last() + 4, 4), ODG_ABORT_TIMEOUT);
    fail_send = 1;
    CHECK_EQ(odg_sdoc_upload(&ch, 0x1000, 0, buf, sizeof buf), ODG_ABORT_HARDWARE);
    CHECK_EQ(ch.state, ODG_SDOC_ABORTED);
    fail_send = 0;
}

/* Two channels, two servers, answers interleaved: each transfer sees only its own. */
static void test_two_in_flight(void)
{
    odg_sdoc_t a, b;
    uint8_t big[9] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    uint8_t buf[4];
    uint8_t d[8] = {0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0};
    const uint8_t up[8] = {0x4B, 0x17, 0x10, 0x00, 0xE8, 0x03, 0, 0};
    n_sent = 0;
    odg_sdoc_init(&a, 2, 0, 0, fake_send, NULL);
    odg_sdoc_init(&b, 3, 0, 0, fake_send, NULL);
    CHECK_EQ(odg_sdoc_download(&a, 0x2000, 0, big, 9), ODG_OK);
    CHECK_EQ(odg_sdoc_upload(&b, 0x1017, 0, buf, sizeof buf), ODG_OK);
    CHECK_EQ(answer(&a, 0x582, d), 1);
    CHECK_EQ(answer(&b, 0x582, d), 0);
    CHECK_EQ(answer(&a, 0x583, up), 0);
    CHECK_EQ(answer(&b, 0x583, up), 1);
    CHECK_EQ(b.state, ODG_SDOC_DONE);
    CHECK_EQ(odg_sdoc_u32(buf, b.n), 1000);
    odg_sdoc_tick(&a, ODG_SDOC_TIMEOUT_MS / 2u);
    d[0] = 0x20;
    CHECK_EQ(answer(&a, 0x582, d), 1);
    odg_sdoc_tick(&a, ODG_SDOC_TIMEOUT_MS / 2u + 1u); /* the timer restarted at the last frame */
    CHECK_EQ(a.state, ODG_SDOC_BUSY);
    d[0] = 0x30;
    CHECK_EQ(answer(&a, 0x582, d), 1);
    CHECK_EQ(a.state, ODG_SDOC_DONE);
    CHECK_EQ(a.n, 9);
}

/* Random answers (a fixed seed) to random transfers: the client never takes more than the upload
 * buffer holds (AddressSanitizer watches the writes) nor sends more than it was given, and every
 * transfer ends (DONE or ABORTED, by an answer or the timeout). */
static void test_random_answers(void)
{
    odg_sdoc_t ch;
    uint8_t buf[12];
    static const uint8_t data[20] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20};
    uint32_t seed = 12345u, round, k, limit;
    uint8_t d[8];
    unsigned ended = 0;
    odg_sdoc_init(&ch, 9, 0, 0, fake_send, NULL);
    for (round = 0; round < 2000u; round++) {
        seed = seed * 1103515245u + 12345u;
        if (seed >> 16 & 1u) {
            limit = sizeof buf;
            (void)odg_sdoc_upload(&ch, 0x2000, 1, buf, sizeof buf);
        } else {
            limit = (seed >> 8) % 21u;
            (void)odg_sdoc_download(&ch, 0x2000, 1, data, limit);
        }
        for (k = 0; k < 6u && ch.state == ODG_SDOC_BUSY; k++) {
            unsigned b;
            for (b = 0; b < 8u; b++) {
                seed = seed * 1103515245u + 12345u;
                d[b] = (uint8_t)(seed >> 16);
            }
            if (k % 2u == 0u) { /* often the right object, so the transfers get going */
                d[1] = 0x00;
                d[2] = 0x20;
                d[3] = 0x01;
            }
            (void)answer(&ch, 0x589, d);
            CHECK(ch.n <= limit);
        }
        odg_sdoc_tick(&ch, ODG_SDOC_TIMEOUT_MS);
        ended += ch.state == ODG_SDOC_DONE || ch.state == ODG_SDOC_ABORTED;
    }
    CHECK_EQ(ended, 2000u);
}

int main(void)
{
    test_expedited_download();
    test_segmented_download();
    test_empty_download();
    test_uploads();
    test_server_abort_and_timeout();
    test_two_in_flight();
    test_random_answers();
    return done();
}
