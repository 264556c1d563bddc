/*
 * test_core.c - odg.c against the hand-written dictionary td: find, read, write, partial
 * transfers, limits, hooks, node-id, PDO mapping, abort texts, typed access, clients, and
 * odg_verify on good and deliberately broken tables. Prints "N passed, M failed"; exit status 0 only when M is 0.
 */
#include <string.h>

#include "check.h"
#include "odg.h"
#include "td.h"

#define NODE 5u

/* ---- helpers -------------------------------------------------------------------------- */

static odg_ref_t ref_of(uint16_t index, uint8_t sub)
{
    odg_ref_t r;
    memset(&r, 0, sizeof r);
    CHECK_EQ_AT(odg_find(&td, index, sub, &r), ODG_OK, index);
    return r;
}

static odg_abort_t wr(uint16_t index, uint8_t sub, const void *buf, uint32_t len)
{
    odg_ref_t r = ref_of(index, sub);
    return odg_write(&r, buf, len);
}

static odg_abort_t wr_part(uint16_t index, uint8_t sub, uint32_t off, const void *buf, uint32_t len,
                           uint32_t total)
{
    odg_ref_t r = ref_of(index, sub);
    return odg_write_part(&r, off, buf, len, total);
}

static void le(uint8_t *b, uint64_t v, uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; i++, v >>= 8) {
        b[i] = (uint8_t)v;
    }
}

/* Write `v` as `n` little-endian bytes. */
static odg_abort_t wrv(uint16_t index, uint8_t sub, uint64_t v, uint32_t n)
{
    uint8_t b[8];
    le(b, v, n);
    return wr(index, sub, b, n);
}

/* Read a whole value; its little-endian number in *v when it has at most 8 bytes. */
static odg_abort_t rd(uint16_t index, uint8_t sub, uint8_t *buf, uint32_t cap, uint32_t *n)
{
    odg_ref_t r = ref_of(index, sub);
    return odg_read(&r, 0, buf, cap, n);
}

static uint64_t rdv(uint16_t index, uint8_t sub)
{
    uint8_t b[64];
    uint32_t n = 0, i;
    uint64_t v = 0;
    CHECK_EQ_AT(rd(index, sub, b, sizeof b, &n), ODG_OK, index);
    for (i = n; i-- > 0u;) {
        v = v << 8 | b[i];
    }
    return v;
}

static uint32_t f2u(float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    return u;
}

static uint64_t d2u(double d)
{
    uint64_t u;
    memcpy(&u, &d, 8);
    return u;
}

static int bytes_eq(const void *a, const void *b, uint32_t n)
{
    return memcmp(a, b, n) == 0;
}

/* ---- expected uploads after odg_init(&td, 5) ----------------------------------------- */

typedef struct {
    uint16_t index;
    uint8_t sub;
    uint32_t len;
    const char *bytes;
} rexp_t;

static const rexp_t uploads[] = {
    {0x1000, 0, 4, "\x91\x01\x02\x00"},
    {0x1008, 0, 8, "odg test"},
    {0x1010, 0, 1, "\x04"},
    {0x1010, 1, 4, "\x01\x00\x00\x00"},
    {0x1010, 4, 4, "\x01\x00\x00\x00"},
    {0x1011, 0, 1, "\x04"},
    {0x1011, 2, 4, "\x01\x00\x00\x00"},
    {0x1014, 0, 4, "\x85\x00\x00\x00"},
    {0x1017, 0, 2, "\xE8\x03"},
    {0x1018, 0, 1, "\x04"},
    {0x1018, 1, 4, "\xCD\xAB\x00\x00"},
    {0x1018, 2, 4, "\x78\x56\x34\x12"},
    {0x1018, 3, 4, "\x02\x00\x01\x00"},
    {0x1018, 4, 4, "\x00\x00\x00\x00"},
    {0x1400, 0, 1, "\x02"},
    {0x1400, 1, 4, "\x05\x02\x00\x00"},
    {0x1400, 2, 1, "\xFE"},
    {0x2001, 0, 1, "\x01"},
    {0x2002, 0, 1, "\xFE"},
    {0x2003, 0, 2, "\xD4\xFE"},
    {0x2004, 0, 4, "\x90\xEE\xFE\xFF"},
    {0x2005, 0, 1, "\xAB"},
    {0x2006, 0, 2, "\xCD\xAB"},
    {0x2007, 0, 4, "\xEF\xCD\xAB\x89"},
    {0x2008, 0, 4, "\x00\x00\xC0\x3F"},
    {0x2009, 0, 3, "abc"},
    {0x200A, 0, 4, "\x01\x02\x03\x04"},
    {0x200B, 0, 4, "h\0i\0"},
    {0x200C, 0, 6, "\xDE\xBC\x0A\x00\x34\x12"},
    {0x200D, 0, 6, "\x05\x00\x00\x00\x07\x00"},
    {0x200F, 0, 3, "\xDE\xAD\xBE"},
    {0x2010, 0, 3, "\xFE\xFF\xFF"},
    {0x2011, 0, 8, "\x00\x00\x00\x00\x00\x00\x02\xC0"},
    {0x2012, 0, 5, "\x00\x00\x00\x00\x80"},
    {0x2013, 0, 6, "\xFF\xFF\xFF\xFF\xFF\x7F"},
    {0x2014, 0, 7, "\xFF\xFF\xFF\xFF\xFF\xFF\xFF"},
    {0x2015, 0, 8, "\x00\x00\x00\x00\x00\x00\x00\x80"},
    {0x2016, 0, 3, "\xBA\xDC\xFE"},
    {0x2018, 0, 5, "\xFF\xFF\xFF\xFF\xFF"},
    {0x2019, 0, 6, "\xBC\x9A\x78\x56\x34\x12"},
    {0x201A, 0, 7, "\x99\xAA\xBB\xCC\xDD\xEE\xFF"},
    {0x201B, 0, 8, "\x10\x32\x54\x76\x98\xBA\xDC\xFE"},
    {0x2100, 0, 1, "\xC8"},
    {0x2100, 1, 2, "\x11\x11"},
    {0x2100, 5, 4, "\x55\x55\x55\x55"},
    {0x2100, 200, 1, "\xC8"},
    {0x2101, 1, 2, "\x01\x00"},
    {0x2101, 2, 2, "\x02\x00"},
    {0x2200, 0, 1, "\x09"},
    {0x2200, 1, 2, "\x00\x00"},
    {0x2200, 2, 4, "\x0A\x00\x00\x00"},
    {0x2200, 3, 4, "\x00\x00\x00\x00"},
    {0x2200, 4, 8, "\x00\x00\x00\x00\x00\x00\xF0\x3F"},
    {0x2200, 5, 3, "\x00\x00\x00"},
    {0x2200, 6, 8, "\x01\x00\x00\x00\x00\x00\x00\x00"},
    {0x2200, 7, 8, "\xF6\xFF\xFF\xFF\xFF\xFF\xFF\xFF"},
    {0x2200, 8, 5, "\x00\x00\x00\x00\x00"},
    {0x2200, 9, 4, "\x00\x00\x00\x00"},
    {0x2300, 0, 1, "\x06"},
    {0x2300, 1, 4, "\x00\x00\x00\x00"},
    {0x2300, 2, 2, "\x00\x00"},
    {0x2300, 3, 1, "\x00"},
    {0x2300, 4, 0, ""},
    {0x2300, 5, 1, "\x00"},
    {0x2300, 6, 0, ""},
    {0x2401, 0, 4, "\x01\x24\x00\x00"},
    {0x2500, 0, 1, "\x05"},
    {0x2500, 1, 4, "\x44\x33\x22\x11"},
    {0x2500, 2, 3, "app"},
    {0x2500, 3, 8, "\xF9\xFF\xFF\xFF\xFF\xFF\xFF\xFF"},
    {0x2500, 4, 2, "\x01\x02"},
    {0x2500, 5, 2, "\x05\x01"},
};
#define N_UPLOADS (sizeof uploads / sizeof uploads[0])

/* ---- hooks used by the tests ---------------------------------------------------------------- */

static struct {
    unsigned calls[8];
    uint16_t index;
    uint8_t sub;
    int had_data;
    uint8_t data[16];
    uint32_t len;
    void *ctx;
    odg_abort_t ret_pre_read, ret_pre_write, ret_post;
    uint32_t refresh;
    unsigned notices;
    uint8_t notice_value;
    uint8_t post_value;
} H;

static odg_abort_t test_hook(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len,
                             void *ctx)
{
    H.calls[kind & 7]++;
    H.index = ref->entry->index;
    H.sub = ref->sub->sub;
    H.had_data = data != NULL;
    H.len = len;
    H.ctx = ctx;
    if (data != NULL && len <= sizeof H.data) {
        memcpy(H.data, data, len);
    }
    if (kind == ODG_HOOK_PRE_READ) {
        if (ref->sub->sub == 1u) {
            td_ram.x2300_s1 = ++H.refresh; /* refresh the value before the upload */
        }
        return H.ret_pre_read;
    }
    if (kind == ODG_HOOK_PRE_WRITE) {
        return H.ret_pre_write;
    }
    H.post_value = td_ram.x2300_s3;
    return H.ret_post;
}

odg_abort_t td_notice(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len,
                      void *ctx)
{
    (void)data;
    (void)len;
    (void)ctx;
    if (kind == ODG_HOOK_POST_WRITE && ref->sub == &td.subs[66]) {
        H.notices++;
        H.notice_value = td_ram.x2300_s3; /* the value is stored before the notice */
    }
    return H.ret_post;
}

static void hooks_clear(void)
{
    memset(&H, 0, sizeof H);
}

/* ---- tests ------------------------------------------------------------------------------------ */

static void test_abort_text(void)
{
#define CODE_(name, text) {name, text},
    static const struct {
        uint32_t code;
        const char *text;
    } codes[] = {ODG_ABORT_CODES(CODE_)};
#undef CODE_
    size_t i;
    for (i = 0; i < sizeof codes / sizeof codes[0]; i++) {
#ifdef ODG_NO_ABORT_TEXT
        CHECK(strcmp(odg_abort_text(codes[i].code), "") == 0);
#else
        CHECK(strcmp(odg_abort_text(codes[i].code), codes[i].text) == 0);
#endif
    }
#ifdef ODG_NO_ABORT_TEXT
    CHECK(strcmp(odg_abort_text(0x12345678u), "") == 0);
#else
    CHECK(strcmp(odg_abort_text(0x12345678u), "unknown abort code") == 0);
    CHECK(strcmp(odg_abort_text(ODG_ABORT_NO_OBJECT), "object does not exist") == 0);
    CHECK(strcmp(odg_abort_text(ODG_ABORT_TOO_LONG), "data type does not match, length too high") == 0);
#endif
    CHECK_EQ(ODG_ABORT_TOO_LONG, 0x06070012u);
    CHECK_EQ(ODG_ABORT_TOO_SHORT, 0x06070013u);
    CHECK_EQ(ODG_ABORT_DATA_STORE, 0x08000020u);
}

static void test_init(void)
{
    CHECK_EQ(odg_init(NULL, NODE), ODG_ABORT_NO_DICTIONARY);
    td_ram.x2007 = 0;
    td.state->boot_seen = 0;
    CHECK_EQ(odg_init(&td, NODE), ODG_OK);
    /* no driver yet: defaults in RAM, NV untouched */
    CHECK_EQ(td.state->boot_seen, 1u << ODG_BOOT_NV_ERROR);
    CHECK_EQ(td.state->node_id, NODE);
    CHECK(td.state->clients == NULL);
    CHECK_EQ(td_ram.x2007, 0x89ABCDEFu); /* reset ran */
    CHECK_EQ(odg_init(&td, NODE), ODG_OK);
}

static void test_find(void)
{
    odg_dict_t sw = td;
    odg_ref_t r, r2;
    uint32_t idx, e;
    unsigned sub;
    sw.find = td_find_switch;
    /* every index: binary search and the switch agree with a linear scan */
    for (idx = 0; idx <= 0xFFFFu; idx++) {
        int present = 0;
        for (e = 0; e < td.n_entries; e++) {
            present |= td.entries[e].index == idx;
        }
        {
            odg_abort_t a = odg_find(&td, (uint16_t)idx, 0, &r);
            odg_abort_t b = odg_find(&sw, (uint16_t)idx, 0, &r2);
            if (idx == 0x2101u) { /* present, but without a sub-index 0 */
                CHECK_EQ(a, ODG_ABORT_NO_SUB);
                CHECK_EQ(b, ODG_ABORT_NO_SUB);
            } else if (present) {
                CHECK_EQ_AT(a, ODG_OK, idx);
                CHECK_EQ_AT(b, ODG_OK, idx);
            } else if (a != ODG_ABORT_NO_OBJECT || b != ODG_ABORT_NO_OBJECT) {
                CHECK_EQ_AT(a, ODG_ABORT_NO_OBJECT, idx);
                CHECK_EQ_AT(b, ODG_ABORT_NO_OBJECT, idx);
            }
        }
    }
    checks_passed++; /* the absent indices above count as one check */
    /* every sub-index of every entry: dense and sparse lookups agree with a linear scan */
    for (e = 0; e < td.n_entries; e++) {
        const odg_entry_t *en = &td.entries[e];
        for (sub = 0; sub <= 255u; sub++) {
            int32_t want = -1;
            uint32_t k;
            odg_abort_t a;
            for (k = en->first; k < (uint32_t)en->first + en->count; k++) {
                if (td.subs[k].sub == sub) {
                    want = (int32_t)k;
                }
            }
            memset(&r, 0, sizeof r);
            a = odg_find(&td, en->index, (uint8_t)sub, &r);
            if (want < 0) {
                if (a != ODG_ABORT_NO_SUB) {
                    CHECK_EQ_AT(a, ODG_ABORT_NO_SUB, sub);
                }
            } else {
                CHECK_EQ_AT(a, ODG_OK, sub);
                CHECK_EQ_AT(r.sub_pos, want, sub);
                CHECK(r.sub == &td.subs[want]);
                CHECK(r.entry == en);
                CHECK(r.dict == &td);
            }
        }
    }
    CHECK_EQ(odg_find(&td, 0x1018, 5, &r), ODG_ABORT_NO_SUB);
    CHECK_EQ(odg_find(&td, 0x2100, 2, &r), ODG_ABORT_NO_SUB);
    CHECK_EQ(odg_find(&td, 0x2100, 255, &r), ODG_ABORT_NO_SUB);
    CHECK_EQ(odg_find(&td, 0x2000, 0, &r), ODG_ABORT_NO_OBJECT);
    CHECK_EQ(odg_find(&td, 0xFFFF, 0, &r), ODG_ABORT_NO_OBJECT);
    CHECK_EQ(odg_find(&td, 0x0000, 0, &r), ODG_ABORT_NO_OBJECT);
}

static void test_reads(void)
{
    size_t i;
    for (i = 0; i < N_UPLOADS; i++) {
        const rexp_t *u = &uploads[i];
        uint8_t buf[32], part[32];
        uint32_t n = 99, off, cap;
        odg_ref_t r = ref_of(u->index, u->sub);
        CHECK_EQ_AT(odg_read(&r, 0, buf, sizeof buf, &n), ODG_OK, i);
        CHECK_EQ_AT(n, u->len, i);
        CHECK_EQ_AT(odg_length(&r), u->len, i);
        CHECK(bytes_eq(buf, u->bytes, u->len));
        /* every offset and buffer size */
        for (off = 0; off <= u->len + 1u; off++) {
            for (cap = 0; cap <= u->len + 1u; cap++) {
                uint32_t want = off >= u->len ? 0u : u->len - off;
                if (want > cap) {
                    want = cap;
                }
                memset(part, 0xEE, sizeof part);
                n = 99;
                CHECK_EQ_AT(odg_read(&r, off, part, cap, &n), ODG_OK, i);
                if (n != want || !bytes_eq(part, u->bytes + (off < u->len ? off : u->len), want) ||
                    part[want] != 0xEE) {
                    CHECK_EQ_AT(n, want, i);
                    CHECK(bytes_eq(part, u->bytes + off, want));
                    CHECK_EQ(part[want], 0xEE);
                }
            }
        }
    }
    checks_passed++;
    {
        uint8_t b[8];
        uint32_t n = 99;
        CHECK_EQ(rd(0x2400, 0, b, sizeof b, &n), ODG_ABORT_WRITE_ONLY);
        CHECK_EQ(n, 0);
    }
}

typedef struct {
    uint16_t index;
    uint32_t size;
} num_t;

static const num_t numerics[] = {
    {0x2001, 1}, {0x2002, 1}, {0x2003, 2}, {0x2004, 4}, {0x2005, 1}, {0x2006, 2}, {0x2007, 4},
    {0x2008, 4}, {0x200C, 6}, {0x200D, 6}, {0x2010, 3}, {0x2011, 8}, {0x2012, 5}, {0x2013, 6},
    {0x2014, 7}, {0x2015, 8}, {0x2016, 3}, {0x2018, 5}, {0x2019, 6}, {0x201A, 7}, {0x201B, 8},
};

static void test_numeric_writes(void)
{
    size_t i;
    uint32_t seed = 12345u;
    for (i = 0; i < sizeof numerics / sizeof numerics[0]; i++) {
        const num_t *t = &numerics[i];
        uint8_t b[9], back[9], before[9];
        uint32_t n, k, round;
        for (round = 0; round < 20u; round++) {
            for (k = 0; k < 9u; k++) {
                seed = seed * 1103515245u + 12345u;
                b[k] = (uint8_t)(seed >> 16);
            }
            if (t->index == 0x2001u) {
                b[0] &= 1u;
            }
            CHECK_EQ_AT(wr(t->index, 0, b, t->size), ODG_OK, t->index);
            CHECK_EQ_AT(rd(t->index, 0, back, sizeof back, &n), ODG_OK, t->index);
            CHECK_EQ_AT(n, t->size, t->index);
            CHECK(bytes_eq(back, b, t->size));
        }
        /* wrong lengths: nothing stored */
        CHECK_EQ(rd(t->index, 0, before, sizeof before, &n), ODG_OK);
        CHECK_EQ_AT(wr(t->index, 0, b, t->size - 1u), ODG_ABORT_TOO_SHORT, t->index);
        CHECK_EQ_AT(wr(t->index, 0, b, t->size + 1u), ODG_ABORT_TOO_LONG, t->index);
        CHECK_EQ_AT(wr(t->index, 0, b, 0), ODG_ABORT_TOO_SHORT, t->index);
        CHECK_EQ(rd(t->index, 0, back, sizeof back, &n), ODG_OK);
        CHECK(bytes_eq(back, before, t->size));
    }
    /* native values: sign extension and widths */
    CHECK_EQ(wrv(0x2002, 0, 0x80, 1), ODG_OK);
    CHECK(td_ram.x2002 == -128);
    CHECK_EQ(wrv(0x2003, 0, 0x8000, 2), ODG_OK);
    CHECK(td_ram.x2003 == -32768);
    CHECK_EQ(wrv(0x2004, 0, 0x80000000u, 4), ODG_OK);
    CHECK(td_ram.x2004 == (-2147483647 - 1));
    CHECK_EQ(wrv(0x2010, 0, 0x800000, 3), ODG_OK);
    CHECK(td_ram.x2010 == -8388608);
    CHECK_EQ(wrv(0x2010, 0, 0x7FFFFF, 3), ODG_OK);
    CHECK(td_ram.x2010 == 8388607);
    CHECK_EQ(wrv(0x2010, 0, 0xFFFFFE, 3), ODG_OK);
    CHECK(td_ram.x2010 == -2);
    CHECK_EQ(wrv(0x2012, 0, UINT64_C(0x8000000000), 5), ODG_OK);
    CHECK(td_ram.x2012 == -INT64_C(549755813888));
    CHECK_EQ(wrv(0x2012, 0, UINT64_C(0x7FFFFFFFFF), 5), ODG_OK);
    CHECK(td_ram.x2012 == INT64_C(549755813887));
    CHECK_EQ(wrv(0x2013, 0, UINT64_C(0x800000000000), 6), ODG_OK);
    CHECK(td_ram.x2013 == -INT64_C(140737488355328));
    CHECK_EQ(wrv(0x2014, 0, UINT64_C(0x80000000000000), 7), ODG_OK);
    CHECK(td_ram.x2014 == -INT64_C(36028797018963968));
    CHECK_EQ(wrv(0x2014, 0, UINT64_C(0xFFFFFFFFFFFFFF), 7), ODG_OK);
    CHECK(td_ram.x2014 == -1);
    CHECK_EQ(wrv(0x2015, 0, UINT64_C(0x8000000000000000), 8), ODG_OK);
    CHECK(td_ram.x2015 == (-INT64_C(9223372036854775807) - 1));
    CHECK_EQ(wrv(0x2016, 0, 0xFFFFFF, 3), ODG_OK);
    CHECK_EQ(td_ram.x2016, 0xFFFFFFu);
    CHECK_EQ(wrv(0x2018, 0, UINT64_C(0xFFFFFFFFFF), 5), ODG_OK);
    CHECK_EQ(td_ram.x2018, UINT64_C(0xFFFFFFFFFF));
    CHECK_EQ(wrv(0x201A, 0, UINT64_C(0x01020304050607), 7), ODG_OK);
    CHECK_EQ(td_ram.x201A, UINT64_C(0x01020304050607));
    CHECK_EQ(wrv(0x201B, 0, UINT64_C(0x0102030405060708), 8), ODG_OK);
    CHECK_EQ(td_ram.x201B, UINT64_C(0x0102030405060708));
    CHECK_EQ(wrv(0x2006, 0, 0x0102, 2), ODG_OK);
    CHECK_EQ(td_ram.x2006, 0x0102u);
    CHECK_EQ(wrv(0x2007, 0, 0x01020304, 4), ODG_OK);
    CHECK_EQ(td_ram.x2007, 0x01020304u);
    CHECK_EQ(wrv(0x2008, 0, f2u(-0.5f), 4), ODG_OK);
    CHECK(td_ram.x2008 == -0.5f);
    CHECK_EQ(wrv(0x2011, 0, d2u(3.75), 8), ODG_OK);
    CHECK(td_ram.x2011 == 3.75);
    CHECK_EQ(wr(0x200C, 0, "\x01\x02\x03\x04\x05\x06", 6), ODG_OK);
    CHECK_EQ(td_ram.x200C, UINT64_C(0x060504030201)); /* ms | days << 32 */
    CHECK_EQ(wrv(0x2100, 200, 0x9C, 1), ODG_OK);
    CHECK(td_ram.x2100_s200 == -100);
    /* BOOLEAN: only 0 and 1 */
    CHECK_EQ(wrv(0x2001, 0, 0, 1), ODG_OK);
    CHECK_EQ(td_ram.x2001, 0);
    CHECK_EQ(wrv(0x2001, 0, 1, 1), ODG_OK);
    CHECK_EQ(td_ram.x2001, 1);
    CHECK_EQ(wrv(0x2001, 0, 2, 1), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(wrv(0x2001, 0, 0xFF, 1), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(td_ram.x2001, 1);
}

static void test_string_writes(void)
{
    uint8_t b[32];
    uint32_t n;
    /* VISIBLE_STRING, capacity 8 */
    CHECK_EQ(wr(0x2009, 0, "hello", 5), ODG_OK);
    CHECK(bytes_eq(td_ram.x2009, "hello\0\0\0\0", 9));
    CHECK_EQ(wr(0x2009, 0, "12345678", 8), ODG_OK);
    CHECK_EQ(rd(0x2009, 0, b, sizeof b, &n), ODG_OK);
    CHECK_EQ(n, 8);
    CHECK(bytes_eq(b, "12345678", 8));
    CHECK_EQ(td_ram.x2009[8], 0);
    CHECK_EQ(wr(0x2009, 0, "123456789", 9), ODG_ABORT_TOO_LONG);
    CHECK(bytes_eq(td_ram.x2009, "12345678", 9));
    CHECK_EQ(wr(0x2009, 0, "xy", 2), ODG_OK);
    CHECK(bytes_eq(td_ram.x2009, "xy\0\0\0\0\0\0\0", 9)); /* a shorter write clears the rest */
    CHECK_EQ(wr(0x2009, 0, "", 0), ODG_OK);
    CHECK_EQ(rd(0x2009, 0, b, sizeof b, &n), ODG_OK);
    CHECK_EQ(n, 0);
    CHECK_EQ(wr(0x2009, 0, "ab\0cd", 5), ODG_OK);
    CHECK_EQ(rdv(0x2009, 0), 0x6261u); /* the length is up to the first NUL */
    /* OCTET_STRING: exactly its capacity (4) */
    CHECK_EQ(wr(0x200A, 0, "\x09\x08\x07\x06", 4), ODG_OK);
    CHECK(bytes_eq(td_ram.x200A, "\x09\x08\x07\x06", 4));
    CHECK_EQ(wr(0x200A, 0, "\x01\x02\x03", 3), ODG_ABORT_TOO_SHORT);
    CHECK_EQ(wr(0x200A, 0, "\x01\x02\x03\x04\x05", 5), ODG_ABORT_TOO_LONG);
    CHECK_EQ(wr(0x200A, 0, "", 0), ODG_ABORT_TOO_SHORT);
    CHECK(bytes_eq(td_ram.x200A, "\x09\x08\x07\x06", 4));
    /* UNICODE_STRING: capacity 8 bytes = 4 units, stored as uint16_t */
    CHECK_EQ(wr(0x200B, 0, "A\0B\0\xAC\x20", 6), ODG_OK);
    CHECK(td_ram.x200B[0] == 'A' && td_ram.x200B[1] == 'B' && td_ram.x200B[2] == 0x20AC &&
          td_ram.x200B[3] == 0 && td_ram.x200B[4] == 0);
    CHECK_EQ(rd(0x200B, 0, b, sizeof b, &n), ODG_OK);
    CHECK_EQ(n, 6);
    CHECK(bytes_eq(b, "A\0B\0\xAC\x20", 6));
    CHECK_EQ(wr(0x200B, 0, "A\0B", 3), ODG_ABORT_TYPE_LENGTH);
    CHECK_EQ(wr(0x200B, 0, "A\0B\0C\0D\0E\0", 10), ODG_ABORT_TOO_LONG);
    CHECK_EQ(wr(0x200B, 0, "A\0B\0C\0D\0", 8), ODG_OK);
    CHECK(td_ram.x200B[3] == 'D' && td_ram.x200B[4] == 0);
    CHECK_EQ(wr(0x200B, 0, "Z\0", 2), ODG_OK);
    CHECK(td_ram.x200B[0] == 'Z' && td_ram.x200B[1] == 0 && td_ram.x200B[3] == 0);
    CHECK_EQ(wr(0x200B, 0, "", 0), ODG_OK);
    CHECK_EQ(rd(0x200B, 0, b, sizeof b, &n), ODG_OK);
    CHECK_EQ(n, 0);
    /* DOMAIN, capacity 16 */
    CHECK_EQ(wr(0x200F, 0, "0123456789abcdef", 16), ODG_OK);
    CHECK_EQ(td_ram.x200F_len, 16);
    CHECK_EQ(rd(0x200F, 0, b, sizeof b, &n), ODG_OK);
    CHECK_EQ(n, 16);
    CHECK(bytes_eq(b, "0123456789abcdef", 16));
    CHECK_EQ(wr(0x200F, 0, "0123456789abcdefg", 17), ODG_ABORT_TOO_LONG);
    CHECK_EQ(td_ram.x200F_len, 16);
    CHECK_EQ(wr(0x200F, 0, "", 0), ODG_OK);
    CHECK_EQ(td_ram.x200F_len, 0);
    td_ram.x200F_len = 1000; /* a corrupt length never reads past the buffer */
    {
        odg_ref_t r = ref_of(0x200F, 0);
        CHECK_EQ(odg_length(&r), 16);
    }
    td_ram.x200F_len = 0;
}

static void test_write_part(void)
{
    uint8_t b[32];
    uint32_t n;
    /* VISIBLE_STRING in three parts */
    CHECK_EQ(wr(0x2009, 0, "zzzzzzzz", 8), ODG_OK);
    CHECK_EQ(wr_part(0x2009, 0, 0, "hel", 3, 6), ODG_OK);
    CHECK_EQ(wr_part(0x2009, 0, 3, "lo", 2, 6), ODG_OK);
    CHECK_EQ(wr_part(0x2009, 0, 5, "!", 1, 6), ODG_OK);
    CHECK(bytes_eq(td_ram.x2009, "hello!\0\0\0", 9));
    CHECK_EQ(wr_part(0x2009, 0, 0, "", 0, 0), ODG_OK); /* empty: complete at once */
    CHECK_EQ(td_ram.x2009[0], 0);
    CHECK_EQ(wr_part(0x2009, 0, 0, "abc", 3, 9), ODG_ABORT_TOO_LONG);
    CHECK_EQ(wr_part(0x2009, 0, 6, "abc", 3, 8), ODG_ABORT_TOO_LONG);
    CHECK_EQ(wr_part(0x2009, 0, 9, "", 0, 8), ODG_ABORT_TOO_LONG);
    CHECK_EQ(wr_part(0x2009, 0, 0xFFFFFFF0u, "abc", 0x20, 8), ODG_ABORT_TOO_LONG);
    /* OCTET_STRING: total must be the capacity */
    CHECK_EQ(wr_part(0x200A, 0, 0, "\x01", 1, 3), ODG_ABORT_TOO_SHORT);
    CHECK_EQ(wr_part(0x200A, 0, 0, "\x0A", 1, 4), ODG_OK);
    CHECK_EQ(wr_part(0x200A, 0, 1, "\x0B", 1, 4), ODG_OK);
    CHECK_EQ(wr_part(0x200A, 0, 2, "\x0C\x0D", 2, 4), ODG_OK);
    CHECK(bytes_eq(td_ram.x200A, "\x0A\x0B\x0C\x0D", 4));
    /* UNICODE_STRING split inside a unit */
    CHECK_EQ(wr_part(0x200B, 0, 0, "\xAC", 1, 6), ODG_OK);
    CHECK_EQ(wr_part(0x200B, 0, 1, "\x20X\0", 3, 6), ODG_OK);
    CHECK_EQ(wr_part(0x200B, 0, 4, "Y\0", 2, 6), ODG_OK);
    CHECK(td_ram.x200B[0] == 0x20AC && td_ram.x200B[1] == 'X' && td_ram.x200B[2] == 'Y' &&
          td_ram.x200B[3] == 0);
    CHECK_EQ(rd(0x200B, 0, b, sizeof b, &n), ODG_OK);
    CHECK_EQ(n, 6);
    CHECK_EQ(wr_part(0x200B, 0, 0, "\x01", 1, 5), ODG_ABORT_TYPE_LENGTH);
    /* DOMAIN: the length changes when the value is complete */
    CHECK_EQ(wr(0x200F, 0, "\x01\x02", 2), ODG_OK);
    CHECK_EQ(wr_part(0x200F, 0, 0, "ABCDE", 5, 16), ODG_OK);
    CHECK_EQ(td_ram.x200F_len, 2);
    CHECK_EQ(wr_part(0x200F, 0, 5, "FGHIJ", 5, 16), ODG_OK);
    CHECK_EQ(wr_part(0x200F, 0, 10, "KLMNO", 5, 16), ODG_OK);
    CHECK_EQ(td_ram.x200F_len, 2);
    CHECK_EQ(wr_part(0x200F, 0, 15, "P", 1, 16), ODG_OK);
    CHECK_EQ(td_ram.x200F_len, 16);
    CHECK(bytes_eq(td_ram.x200F_buf, "ABCDEFGHIJKLMNOP", 16));
    CHECK_EQ(wr_part(0x200F, 0, 0, "A", 1, 17), ODG_ABORT_TOO_LONG);
    /* numbers: whole values only */
    CHECK_EQ(wr_part(0x2007, 0, 0, "\x04\x03\x02\x01", 4, 4), ODG_OK);
    CHECK_EQ(td_ram.x2007, 0x01020304u);
    CHECK_EQ(wr_part(0x2007, 0, 0, "\x04\x03", 2, 4), ODG_ABORT_UNSUPPORTED);
    CHECK_EQ(wr_part(0x2007, 0, 2, "\x04\x03", 2, 4), ODG_ABORT_UNSUPPORTED);
    CHECK_EQ(wr_part(0x2007, 0, 0, "\x04\x03", 2, 3), ODG_ABORT_TOO_SHORT);
    CHECK_EQ(wr_part(0x2007, 0, 0, "\x04\x03", 2, 5), ODG_ABORT_TOO_LONG);
    CHECK_EQ(td_ram.x2007, 0x01020304u);
    /* access */
    CHECK_EQ(wr_part(0x1000, 0, 0, "\x04\x03\x02\x01", 4, 4), ODG_ABORT_READ_ONLY);
    CHECK_EQ(wr_part(0x1000, 0, 0, "\x04\x03", 2, 4), ODG_ABORT_READ_ONLY);
    CHECK_EQ(wr_part(0x1008, 0, 0, "abc", 3, 3), ODG_ABORT_READ_ONLY);
}

static void test_access(void)
{
    uint8_t b[8];
    uint32_t n = 7;
    CHECK_EQ(wrv(0x1000, 0, 1, 4), ODG_ABORT_READ_ONLY);
    CHECK_EQ(wr(0x1008, 0, "x", 1), ODG_ABORT_READ_ONLY);
    CHECK_EQ(wrv(0x1010, 0, 1, 1), ODG_ABORT_READ_ONLY);
    CHECK_EQ(wrv(0x1018, 4, 1, 4), ODG_ABORT_READ_ONLY);
    CHECK_EQ(wrv(0x2401, 0, 1, 4), ODG_ABORT_READ_ONLY);
    CHECK_EQ(wrv(0x2401, 0, 1, 3), ODG_ABORT_READ_ONLY); /* access before length */
    CHECK_EQ(rd(0x2400, 0, b, sizeof b, &n), ODG_ABORT_WRITE_ONLY);
    CHECK_EQ(n, 0);
    CHECK_EQ(wrv(0x2400, 0, 0xCAFE, 4), ODG_OK);
    CHECK_EQ(td_ram.x2400, 0xCAFEu);
    {
        /* a FLASH value is never written, even if its descriptor claims write access */
        odg_sub_t s = {offsetof(td_rom_t, x1000), 4, 0, ODG_T_UNSIGNED32, ODG_A_READ | ODG_A_WRITE,
                       ODG_S_ROM};
        odg_ref_t r = ref_of(0x1000, 0);
        r.sub = &s;
        CHECK_EQ(odg_write(&r, "\x01\x00\x00\x00", 4), ODG_ABORT_READ_ONLY);
        CHECK_EQ(odg_write_part(&r, 0, "\x01\x00\x00\x00", 4, 4), ODG_ABORT_READ_ONLY);
        CHECK_EQ(td_rom.x1000, 0x00020191u);
    }
    /* 0x1010/0x1011 without an NV driver */
    CHECK_EQ(rdv(0x1010, 1), 1u);
    CHECK_EQ(rdv(0x1011, 3), 1u);
    CHECK_EQ(wr(0x1010, 1, "save", 4), ODG_ABORT_DATA_STORE);
    CHECK_EQ(wr(0x1011, 1, "load", 4), ODG_ABORT_DATA_STORE);
    CHECK_EQ(wr(0x1010, 1, "sav", 3), ODG_ABORT_TOO_SHORT);
    CHECK_EQ(wr(0x1010, 1, "saves", 5), ODG_ABORT_TOO_LONG);
    CHECK_EQ(wr(0x1010, 1, "evas", 4), ODG_ABORT_DATA_STORE);
}

static void test_limits(void)
{
    float f;
    uint32_t u;
    /* INTEGER16 -100..100 */
    CHECK_EQ(wrv(0x2200, 1, (uint16_t)-100, 2), ODG_OK);
    CHECK_EQ(wrv(0x2200, 1, 100, 2), ODG_OK);
    CHECK_EQ(wrv(0x2200, 1, 101, 2), ODG_ABORT_VALUE_HIGH);
    CHECK_EQ(wrv(0x2200, 1, (uint16_t)-101, 2), ODG_ABORT_VALUE_LOW);
    CHECK_EQ(wrv(0x2200, 1, 0x7FFF, 2), ODG_ABORT_VALUE_HIGH);
    CHECK_EQ(wrv(0x2200, 1, 0x8000, 2), ODG_ABORT_VALUE_LOW);
    CHECK(td_ram.x2200_s1 == 100);
    /* UNSIGNED32 10..1000 */
    CHECK_EQ(wrv(0x2200, 2, 9, 4), ODG_ABORT_VALUE_LOW);
    CHECK_EQ(wrv(0x2200, 2, 0, 4), ODG_ABORT_VALUE_LOW);
    CHECK_EQ(wrv(0x2200, 2, 10, 4), ODG_OK);
    CHECK_EQ(wrv(0x2200, 2, 1000, 4), ODG_OK);
    CHECK_EQ(wrv(0x2200, 2, 1001, 4), ODG_ABORT_VALUE_HIGH);
    CHECK_EQ(wrv(0x2200, 2, 0xFFFFFFFFu, 4), ODG_ABORT_VALUE_HIGH); /* not -1 */
    CHECK_EQ(td_ram.x2200_s2, 1000);
    /* REAL32 -1.5..2.5 */
    CHECK_EQ(wrv(0x2200, 3, f2u(-1.5f), 4), ODG_OK);
    CHECK_EQ(wrv(0x2200, 3, f2u(2.5f), 4), ODG_OK);
    CHECK_EQ(wrv(0x2200, 3, f2u(2.5f) + 1u, 4), ODG_ABORT_VALUE_HIGH); /* next float up */
    CHECK_EQ(wrv(0x2200, 3, f2u(-1.5f) + 1u, 4), ODG_ABORT_VALUE_LOW); /* next float down */
    CHECK_EQ(wrv(0x2200, 3, 0x7F800000u, 4), ODG_ABORT_VALUE_HIGH); /* +inf */
    CHECK_EQ(wrv(0x2200, 3, 0xFF800000u, 4), ODG_ABORT_VALUE_LOW);  /* -inf */
    CHECK_EQ(wrv(0x2200, 3, 0x7FC00000u, 4), ODG_ABORT_VALUE_RANGE); /* NaN */
    CHECK_EQ(wrv(0x2200, 3, 0x80000000u, 4), ODG_OK);               /* -0 */
    CHECK_EQ(wrv(0x2200, 3, f2u(1.25f), 4), ODG_OK);
    CHECK(td_ram.x2200_s3 == 1.25f);
    /* REAL32 -0.1..0.1: a limit float cannot represent admits the float nearest to it
     * (float 0.1 is a little above the double 0.1, float -0.1 a little below -0.1) */
    f = 0.1f;
    memcpy(&u, &f, 4);
    CHECK_EQ(wrv(0x2200, 9, u, 4), ODG_OK);
    CHECK_EQ(wrv(0x2200, 9, u + 1u, 4), ODG_ABORT_VALUE_HIGH);
    f = -0.1f;
    memcpy(&u, &f, 4);
    CHECK_EQ(wrv(0x2200, 9, u, 4), ODG_OK);
    CHECK_EQ(wrv(0x2200, 9, u + 1u, 4), ODG_ABORT_VALUE_LOW);
    CHECK_EQ(wrv(0x2200, 9, f2u(-0.2f), 4), ODG_ABORT_VALUE_LOW);
    /* REAL64 -1000..1000 */
    CHECK_EQ(wrv(0x2200, 4, d2u(1000.0), 8), ODG_OK);
    CHECK_EQ(wrv(0x2200, 4, d2u(-1000.0), 8), ODG_OK);
    CHECK_EQ(wrv(0x2200, 4, d2u(1000.0) + 1u, 8), ODG_ABORT_VALUE_HIGH);
    CHECK_EQ(wrv(0x2200, 4, d2u(-1000.0) + 1u, 8), ODG_ABORT_VALUE_LOW);
    CHECK_EQ(wrv(0x2200, 4, UINT64_C(0x7FF8000000000000), 8), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(wrv(0x2200, 4, d2u(-3.5), 8), ODG_OK);
    CHECK(td_ram.x2200_s4 == -3.5);
    /* INTEGER24 -8000000..8000000 */
    CHECK_EQ(wrv(0x2200, 5, (uint32_t)-8000000, 3), ODG_OK);
    CHECK_EQ(wrv(0x2200, 5, 8000000, 3), ODG_OK);
    CHECK_EQ(wrv(0x2200, 5, (uint32_t)-8000001, 3), ODG_ABORT_VALUE_LOW);
    CHECK_EQ(wrv(0x2200, 5, 8000001, 3), ODG_ABORT_VALUE_HIGH);
    CHECK_EQ(wrv(0x2200, 5, 0x800000, 3), ODG_ABORT_VALUE_LOW);
    CHECK_EQ(wrv(0x2200, 5, 0x7FFFFF, 3), ODG_ABORT_VALUE_HIGH);
    CHECK(td_ram.x2200_s5 == 8000000);
    /* UNSIGNED64 1..2^64-16 */
    CHECK_EQ(wrv(0x2200, 6, 0, 8), ODG_ABORT_VALUE_LOW);
    CHECK_EQ(wrv(0x2200, 6, UINT64_C(0xFFFFFFFFFFFFFFF1), 8), ODG_ABORT_VALUE_HIGH);
    CHECK_EQ(wrv(0x2200, 6, UINT64_C(0xFFFFFFFFFFFFFFF0), 8), ODG_OK);
    CHECK_EQ(wrv(0x2200, 6, UINT64_C(0x8000000000000000), 8), ODG_OK);
    CHECK_EQ(td_ram.x2200_s6, UINT64_C(0x8000000000000000));
    /* INTEGER64 -2^63+1..-5 */
    CHECK_EQ(wrv(0x2200, 7, (uint64_t)-5, 8), ODG_OK);
    CHECK_EQ(wrv(0x2200, 7, (uint64_t)-4, 8), ODG_ABORT_VALUE_HIGH);
    CHECK_EQ(wrv(0x2200, 7, 0, 8), ODG_ABORT_VALUE_HIGH);
    CHECK_EQ(wrv(0x2200, 7, UINT64_C(0x7FFFFFFFFFFFFFFF), 8), ODG_ABORT_VALUE_HIGH);
    CHECK_EQ(wrv(0x2200, 7, UINT64_C(0x8000000000000000), 8), ODG_ABORT_VALUE_LOW);
    CHECK_EQ(wrv(0x2200, 7, UINT64_C(0x8000000000000001), 8), ODG_OK);
    CHECK(td_ram.x2200_s7 == -INT64_C(9223372036854775807));
    /* INTEGER40 with limits over its whole range */
    CHECK_EQ(wrv(0x2200, 8, UINT64_C(0x8000000000), 5), ODG_OK);
    CHECK_EQ(wrv(0x2200, 8, UINT64_C(0x7FFFFFFFFF), 5), ODG_OK);
    CHECK(td_ram.x2200_s8 == INT64_C(549755813887));
    /* limits checked before the value changes and before any hook */
    CHECK_EQ(wrv(0x2500, 3, 1000001, 8), ODG_ABORT_VALUE_HIGH);
    CHECK_EQ(wrv(0x2500, 3, (uint64_t)-1000001, 8), ODG_ABORT_VALUE_LOW);
    CHECK(td_persist_app.x2500_s3 == -7);
}

static void test_hooks(void)
{
    uint8_t b[16];
    uint32_t n;
    odg_ref_t r;
    hooks_clear();
    /* registration */
    CHECK_EQ(odg_hook_register(&td, 0x2001, 0, test_hook, NULL), ODG_ABORT_UNSUPPORTED);
    CHECK_EQ(odg_hook_register(&td, 0x2300, 0, test_hook, NULL), ODG_ABORT_UNSUPPORTED);
    CHECK_EQ(odg_hook_register(&td, 0x3000, 0, test_hook, NULL), ODG_ABORT_NO_OBJECT);
    CHECK_EQ(odg_hook_register(&td, 0x2300, 9, test_hook, NULL), ODG_ABORT_NO_SUB);
    /* PRE_READ refreshes the value */
    CHECK_EQ(odg_hook_register(&td, 0x2300, 1, test_hook, &H), ODG_OK);
    CHECK_EQ(rdv(0x2300, 1), 1u);
    CHECK_EQ(H.calls[ODG_HOOK_PRE_READ], 1);
    CHECK(H.ctx == &H);
    CHECK(H.index == 0x2300 && H.sub == 1 && !H.had_data && H.len == 0);
    CHECK_EQ(rdv(0x2300, 1), 2u);
    r = ref_of(0x2300, 1);
    CHECK_EQ(odg_read(&r, 2, b, sizeof b, &n), ODG_OK); /* later segments: no hook */
    CHECK_EQ(n, 2);
    CHECK_EQ(H.calls[ODG_HOOK_PRE_READ], 2);
    H.ret_pre_read = ODG_ABORT_DATA_STATE;
    n = 9;
    CHECK_EQ(odg_read(&r, 0, b, sizeof b, &n), ODG_ABORT_DATA_STATE);
    CHECK_EQ(n, 0);
    H.ret_pre_read = ODG_OK;
    CHECK_EQ(odg_check_mapping(&td, 0x23000120u, ODG_A_TPDO, NULL), ODG_OK);
    /* PRE_WRITE may veto; it sees the wire value */
    CHECK_EQ(odg_hook_register(&td, 0x2300, 2, test_hook, NULL), ODG_OK);
    H.ret_pre_write = ODG_ABORT_VALUE_RANGE;
    CHECK_EQ(wrv(0x2300, 2, 0x1234, 2), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(td_ram.x2300_s2, 0);
    CHECK(H.had_data && H.len == 2 && H.data[0] == 0x34 && H.data[1] == 0x12);
    CHECK(H.index == 0x2300 && H.sub == 2);
    H.ret_pre_write = ODG_OK;
    CHECK_EQ(wrv(0x2300, 2, 0x1234, 2), ODG_OK);
    CHECK_EQ(td_ram.x2300_s2, 0x1234);
    CHECK_EQ(H.calls[ODG_HOOK_PRE_WRITE], 2);
    CHECK_EQ(wrv(0x2300, 2, 0x1234, 3), ODG_ABORT_TOO_LONG); /* checks before hooks */
    CHECK_EQ(H.calls[ODG_HOOK_PRE_WRITE], 2);
    (void)rdv(0x2300, 2); /* only declared kinds run */
    CHECK_EQ(H.calls[ODG_HOOK_PRE_READ], 3);
    CHECK_EQ(H.calls[ODG_HOOK_POST_WRITE], 0);
    /* POST_WRITE: the statically registered td_notice sees the stored value */
    CHECK_EQ(wrv(0x2300, 3, 7, 1), ODG_OK);
    CHECK_EQ(H.notices, 1);
    CHECK_EQ(H.notice_value, 7);
    H.ret_post = ODG_ABORT_GENERAL; /* passed back; the value stays stored */
    CHECK_EQ(wrv(0x2300, 3, 9, 1), ODG_ABORT_GENERAL);
    CHECK_EQ(td_ram.x2300_s3, 9);
    H.ret_post = ODG_OK;
    CHECK_EQ(odg_hook_register(&td, 0x2300, 3, test_hook, NULL), ODG_OK);
    CHECK_EQ(wrv(0x2300, 3, 11, 1), ODG_OK);
    CHECK_EQ(H.notices, 2);
    CHECK_EQ(H.calls[ODG_HOOK_POST_WRITE], 1);
    CHECK_EQ(H.post_value, 11);
    CHECK(!H.had_data && H.len == 0);
    CHECK_EQ(odg_hook_register(&td, 0x2300, 3, NULL, NULL), ODG_OK); /* unregister */
    CHECK_EQ(wrv(0x2300, 3, 12, 1), ODG_OK);
    CHECK_EQ(H.calls[ODG_HOOK_POST_WRITE], 1);
    CHECK_EQ(odg_hook_register(&td, 0x2300, 3, td_notice, NULL), ODG_OK);
    /* a string with PRE_WRITE and POST_WRITE, whole and in parts */
    memset(H.calls, 0, sizeof H.calls);
    CHECK_EQ(odg_hook_register(&td, 0x2300, 4, test_hook, NULL), ODG_OK);
    CHECK_EQ(wr(0x2300, 4, "hey", 3), ODG_OK);
    CHECK(H.calls[ODG_HOOK_PRE_WRITE] == 1 && H.calls[ODG_HOOK_POST_WRITE] == 1);
    CHECK(bytes_eq(td_ram.x2300_s4, "hey", 4));
    H.ret_pre_write = ODG_ABORT_DATA_LOCAL;
    CHECK_EQ(wr(0x2300, 4, "no", 2), ODG_ABORT_DATA_LOCAL);
    CHECK(bytes_eq(td_ram.x2300_s4, "hey", 4));
    CHECK(H.had_data && H.len == 2 && bytes_eq(H.data, "no", 2));
    CHECK_EQ(wr_part(0x2300, 4, 0, "ab", 2, 4), ODG_ABORT_DATA_LOCAL);
    CHECK(bytes_eq(td_ram.x2300_s4, "hey", 4));
    CHECK(!H.had_data && H.len == 4); /* in parts: no data, the total length */
    H.ret_pre_write = ODG_OK;
    memset(H.calls, 0, sizeof H.calls);
    CHECK_EQ(wr_part(0x2300, 4, 0, "ab", 2, 4), ODG_OK);
    CHECK(H.calls[ODG_HOOK_PRE_WRITE] == 1 && H.calls[ODG_HOOK_POST_WRITE] == 0);
    CHECK_EQ(wr_part(0x2300, 4, 2, "cd", 2, 4), ODG_OK);
    CHECK(H.calls[ODG_HOOK_PRE_WRITE] == 1 && H.calls[ODG_HOOK_POST_WRITE] == 1);
    CHECK(bytes_eq(td_ram.x2300_s4, "abcd", 5));
    /* declared but never registered: nothing runs */
    memset(H.calls, 0, sizeof H.calls);
    CHECK_EQ(wrv(0x2300, 5, 3, 1), ODG_OK);
    CHECK_EQ(td_ram.x2300_s5, 3);
    CHECK(H.calls[ODG_HOOK_PRE_WRITE] == 0 && H.calls[ODG_HOOK_POST_WRITE] == 0);
    /* a domain with all three kinds */
    CHECK_EQ(odg_hook_register(&td, 0x2300, 6, test_hook, NULL), ODG_OK);
    CHECK_EQ(wr(0x2300, 6, "\x01\x02\x03", 3), ODG_OK);
    CHECK(H.calls[ODG_HOOK_PRE_WRITE] == 1 && H.calls[ODG_HOOK_POST_WRITE] == 1);
    CHECK_EQ(rd(0x2300, 6, b, sizeof b, &n), ODG_OK);
    CHECK_EQ(n, 3);
    CHECK_EQ(H.calls[ODG_HOOK_PRE_READ], 1);
    CHECK_EQ(wr(0x2300, 6, "123456789", 9), ODG_ABORT_TOO_LONG);
    CHECK_EQ(H.calls[ODG_HOOK_PRE_WRITE], 1);
    /* leave the slots as the generated table had them */
    (void)odg_hook_register(&td, 0x2300, 1, NULL, NULL);
    (void)odg_hook_register(&td, 0x2300, 2, NULL, NULL);
    (void)odg_hook_register(&td, 0x2300, 4, NULL, NULL);
    (void)odg_hook_register(&td, 0x2300, 6, NULL, NULL);
    hooks_clear();
}

static void test_node_id(void)
{
    CHECK_EQ(wrv(0x1014, 0, 0x1234, 4), ODG_OK);
    CHECK_EQ(odg_init(&td, 127), ODG_OK);
    CHECK_EQ(rdv(0x1014, 0), 0xFFu);
    CHECK_EQ(rdv(0x1400, 1), 0x27Fu);
    CHECK_EQ(rdv(0x2500, 5), 0x17Fu);
    CHECK_EQ(odg_init(&td, 1), ODG_OK);
    CHECK_EQ(rdv(0x1014, 0), 0x81u);
    CHECK_EQ(rdv(0x1400, 1), 0x201u);
    CHECK_EQ(rdv(0x2500, 5), 0x101u);
    CHECK_EQ(rdv(0x1000, 0), 0x00020191u); /* others untouched */
    CHECK_EQ(odg_init(&td, NODE), ODG_OK);
    CHECK_EQ(rdv(0x1014, 0), 0x85u);
}

static void test_mapping(void)
{
    odg_ref_t r;
    memset(&r, 0, sizeof r);
    CHECK_EQ(odg_check_mapping(&td, 0x20070020u, ODG_A_TPDO, &r), ODG_OK);
    CHECK(r.sub == &td.subs[28]);
    CHECK_EQ(odg_check_mapping(&td, 0x20070020u, ODG_A_RPDO, NULL), ODG_OK);
    CHECK_EQ(odg_check_mapping(&td, 0x20070010u, ODG_A_TPDO, NULL), ODG_ABORT_NOT_MAPPABLE);
    CHECK_EQ(odg_check_mapping(&td, 0x20070021u, ODG_A_TPDO, NULL), ODG_ABORT_NOT_MAPPABLE);
    CHECK_EQ(odg_check_mapping(&td, 0x20070000u, ODG_A_TPDO, NULL), ODG_ABORT_NOT_MAPPABLE);
    CHECK_EQ(odg_check_mapping(&td, 0x20010001u, ODG_A_TPDO, NULL), ODG_OK); /* BOOLEAN: 1 bit */
    CHECK_EQ(odg_check_mapping(&td, 0x20010008u, ODG_A_RPDO, NULL), ODG_OK); /* or 8 */
    CHECK_EQ(odg_check_mapping(&td, 0x20010002u, ODG_A_TPDO, NULL), ODG_ABORT_NOT_MAPPABLE);
    CHECK_EQ(odg_check_mapping(&td, 0x20100018u, ODG_A_TPDO, NULL), ODG_OK); /* INTEGER24 */
    CHECK_EQ(odg_check_mapping(&td, 0x200C0030u, ODG_A_TPDO, NULL), ODG_OK); /* TIME_OF_DAY */
    CHECK_EQ(odg_check_mapping(&td, 0x201B0040u, ODG_A_RPDO, NULL), ODG_OK);
    CHECK_EQ(odg_check_mapping(&td, 0x10180420u, ODG_A_TPDO, NULL), ODG_OK);
    CHECK_EQ(odg_check_mapping(&td, 0x10180420u, ODG_A_RPDO, NULL), ODG_ABORT_NOT_MAPPABLE);
    CHECK_EQ(odg_check_mapping(&td, 0x24000020u, ODG_A_RPDO, NULL), ODG_OK);
    CHECK_EQ(odg_check_mapping(&td, 0x24000020u, ODG_A_TPDO, NULL), ODG_ABORT_NOT_MAPPABLE);
    CHECK_EQ(odg_check_mapping(&td, 0x20090040u, ODG_A_TPDO, NULL), ODG_ABORT_NOT_MAPPABLE);
    CHECK_EQ(odg_check_mapping(&td, 0x10000020u, ODG_A_TPDO, NULL), ODG_ABORT_NOT_MAPPABLE);
    CHECK_EQ(odg_check_mapping(&td, 0x20070020u, 0, NULL), ODG_ABORT_NOT_MAPPABLE);
    CHECK_EQ(odg_check_mapping(&td, 0x30000020u, ODG_A_TPDO, NULL), ODG_ABORT_NO_OBJECT);
    CHECK_EQ(odg_check_mapping(&td, 0x20070120u, ODG_A_TPDO, NULL), ODG_ABORT_NO_SUB);
}

/* ---- odg_verify ------------------------------------------------------------------------------- */

static odg_entry_t E[TD_N_ENTRIES];
static odg_sub_t S[TD_N_SUBS + 1];
static odg_limit_t L[TD_N_LIMITS];
static odg_domain_t DOM[TD_N_DOMAINS];
static odg_hook_map_t HM[TD_N_HOOKS];
static odg_group_t G[2];
static odg_dict_t D;

static void fresh(void)
{
    memcpy(E, td.entries, sizeof E);
    memcpy(S, td.subs, TD_N_SUBS * sizeof S[0]);
    S[TD_N_SUBS] = S[TD_N_SUBS - 1];
    memcpy(L, td.limits, sizeof L);
    memcpy(DOM, td.domains, sizeof DOM);
    memcpy(HM, td.hook_map, sizeof HM);
    memcpy(G, td.groups, sizeof G);
    D = td;
    D.entries = E;
    D.subs = S;
    D.limits = L;
    D.domains = DOM;
    D.hook_map = HM;
    D.groups = G;
}

static int32_t find_all_zero(uint16_t index)
{
    (void)index;
    return 0;
}

static int32_t find_claims_0x1015(uint16_t index)
{
    return index == 0x1015u ? 5 : td_find_switch(index);
}

#define BAD(expect_index)                                                    \
    do {                                                                     \
        uint16_t bad_ = 0x1234;                                              \
        CHECK_EQ(odg_verify(&D, &bad_), ODG_ABORT_INTERNAL);                 \
        CHECK_EQ(bad_, (expect_index));                                      \
        fresh();                                                             \
    } while (0)

/* Bad runs of a group's defaults (odg_group_t.spread). */
static const uint16_t beyond[4] = {0, sizeof(td_persist_app_t) + 1u, 0, 0};
static const uint16_t backwards[6] = {8, 12, 0, 4, 0, 0};
static const uint16_t empty_run[4] = {4, 4, 0, 0};

static void test_verify(void)
{
    uint16_t bad = 0x1234;
    td_persist_app_t defaults;
    odg_dict_t sw = td;
    CHECK_EQ(odg_verify(&td, &bad), ODG_OK);
    CHECK_EQ(bad, 0);
    CHECK_EQ(odg_verify(&td, NULL), ODG_OK);
    sw.find = td_find_switch;
    CHECK_EQ(odg_verify(&sw, &bad), ODG_OK);
    CHECK_EQ(odg_verify(NULL, &bad), ODG_ABORT_INTERNAL);
    CHECK_EQ(bad, 0xFFFF);
    fresh();
    CHECK_EQ(odg_verify(&D, &bad), ODG_OK);
    /* entries */
    E[10].index = 0x2002;
    BAD(0x2002); /* duplicate */
    E[10].index = 0x2000;
    BAD(0x2000); /* out of order */
    E[33].first = 48;
    BAD(0x2100);
    E[37].count = 0;
    BAD(0x2400);
    E[39].count = 7;
    BAD(0x2500);
    E[33].code |= ODG_E_DENSE;
    BAD(0x2100); /* subs 0, 1, 5, 200 are not dense */
    E[34].code |= ODG_E_DENSE;
    BAD(0x2101); /* no sub 0 */
    D.n_subs = 77;
    BAD(0x2500);
    D.n_subs = 79;
    BAD(0xFFFF);
    D.find = find_all_zero;
    BAD(0x1000);
    D.find = find_claims_0x1015;
    BAD(0x1014);
    /* sub-entries */
    S[48].sub = 5;
    BAD(0x2100);
    S[48].sub = 6;
    BAD(0x2100);
    S[28].type = 0x0E;
    BAD(0x2007);
    S[28].type = 0x17;
    BAD(0x2007);
    S[28].type = 0x1C;
    BAD(0x2007);
    S[28].type = 0x00;
    BAD(0x2007);
    S[28].size = 3;
    BAD(0x2007);
    S[36].size = 4;
    BAD(0x2010);
    S[33].size = 8;
    BAD(0x200C);
    S[28].storage = 0x05;
    BAD(0x2007);
    S[28].attr |= 0x80u;
    BAD(0x2007);
    S[3].offset = 4; /* a command has no value */
    BAD(0x1010);
    S[3].type = ODG_T_UNSIGNED16;
    BAD(0x1010);
    S[3].size = 2;
    BAD(0x1010);
    S[3].attr |= ODG_A_NODEID;
    BAD(0x1010);
    S[3].storage = ODG_S_COMMAND | 0x04u;
    BAD(0x1010);
    S[0].attr |= ODG_A_WRITE;
    BAD(0x1000);
    S[0].attr |= ODG_A_NODEID;
    BAD(0x1000);
    S[29].attr |= ODG_A_NODEID;
    BAD(0x2008);
    S[30].attr |= ODG_A_LIMIT;
    BAD(0x2009);
    S[30].attr |= ODG_A_NODEID;
    BAD(0x2009);
    S[32].size = 7;
    BAD(0x200B);
    /* where values lie: the block of the class is there, the offset aligned for the C type */
    D.rom = NULL;
    BAD(0x1000);
    D.ram = NULL;
    BAD(0x1014);
    S[28].offset = (uint16_t)(S[28].offset + 2u); /* UNSIGNED32 */
    BAD(0x2007);
    S[28].offset = (uint16_t)(S[28].offset + 1u);
    BAD(0x2007);
    S[27].offset = (uint16_t)(S[27].offset + 1u); /* UNSIGNED16 */
    BAD(0x2006);
    S[29].offset = (uint16_t)(S[29].offset + 2u); /* REAL32 */
    BAD(0x2008);
    S[36].offset = (uint16_t)(S[36].offset + 1u); /* INTEGER24 in an int32_t */
    BAD(0x2010);
    S[41].offset = (uint16_t)(S[41].offset + 2u); /* INTEGER64 */
    BAD(0x2015);
    S[37].offset = (uint16_t)(S[37].offset + 1u); /* REAL64 */
    BAD(0x2011);
    S[32].offset = (uint16_t)(S[32].offset + 1u); /* UNICODE_STRING: uint16_t units */
    BAD(0x200B);
    S[15].offset = (uint16_t)(S[15].offset + 2u); /* in the ROM block */
    BAD(0x1018);
    S[26].offset = offsetof(td_ram_t, x2002); /* a byte may lie anywhere (here: on another) */
    CHECK_EQ(odg_verify(&D, &bad), ODG_OK);
    fresh();
    /* domains: an index into the domain table, whose descriptor fits the sub-entry */
    S[35].offset = TD_N_DOMAINS;
    BAD(0x200F);
    S[35].offset = 0xFFFF;
    BAD(0x200F);
    D.n_domains = TD_N_DOMAINS - 1u; /* 0x2500sub4 has the last one */
    BAD(0x2500);
    D.domains = NULL;
    BAD(0xFFFF);
    S[35].offset = 1; /* a domain of capacity 8 for a sub-entry of 16 */
    BAD(0x200F);
    S[69].offset = 0; /* capacity 16 for 8 is fine */
    CHECK_EQ(odg_verify(&D, &bad), ODG_OK);
    fresh();
    /* limits: ordered by the type's class */
    L[0].low = 100;
    L[0].high = (uint64_t)-100;
    BAD(0x2200);
    L[1].low = 1000;
    L[1].high = 10;
    BAD(0x2200);
    L[2].low = d2u(2.5);
    L[2].high = d2u(-1.5);
    BAD(0x2200);
    L[3].low = UINT64_C(0x7FF8000000000000); /* NaN */
    BAD(0x2200);
    L[2].high = d2u(1e300); /* a REAL32 limit beyond the float range */
    BAD(0x2200);
    L[2].high = UINT64_C(0x7FF0000000000000); /* +inf is fine */
    CHECK_EQ(odg_verify(&D, &bad), ODG_OK);
    L[3].high = UINT64_C(0x7FF0000000000000);
    CHECK_EQ(odg_verify(&D, &bad), ODG_OK);
    fresh();
    L[5].low = UINT64_C(0xFFFFFFFFFFFFFFF0); /* ordered if read as signed, not as unsigned */
    L[5].high = 1;
    BAD(0x2200);
    /* limits: sorted by sub position, one for each ODG_A_LIMIT sub-entry and for no other */
    D.limits = NULL;
    BAD(0xFFFF);
    D.limits = NULL;
    D.n_limits = 0;
    BAD(0x2200); /* ODG_A_LIMIT without limits */
    D.n_limits = TD_N_LIMITS - 1u; /* the last, 0x2500sub3's, cut off */
    BAD(0x2500);
    S[28].attr |= ODG_A_LIMIT;
    BAD(0x2007);
    S[54].attr &= (uint8_t)~ODG_A_LIMIT; /* limits for a sub-entry without ODG_A_LIMIT */
    BAD(0x2200);
    S[75].attr &= (uint8_t)~ODG_A_LIMIT;
    BAD(0x2500);
    L[0].sub_pos = 53; /* 0x2200sub0 */
    BAD(0x2200);
    L[9].sub_pos = TD_N_SUBS;
    BAD(0xFFFF);
    {
        odg_limit_t l = L[0]; /* unsorted */
        L[0] = L[1];
        L[1] = l;
    }
    BAD(0x2200);
    L[9].sub_pos = 61; /* after 62 */
    BAD(0x2200);
    L[4].sub_pos = L[3].sub_pos; /* twice */
    BAD(0x2200);
    /* current values */
    td_ram.x2200_s1 = 101;
    BAD(0x2200);
    td_ram.x2200_s1 = 0;
    td_ram.x2200_s3 = 3.0f;
    BAD(0x2200);
    td_ram.x2200_s3 = 0.0f;
    td_ram.x2001 = 2;
    BAD(0x2001);
    td_ram.x2001 = 1;
    td_ram.x2009[8] = 'x';
    BAD(0x2009);
    td_ram.x2009[8] = 0;
    td_ram.x200B[4] = 'x';
    BAD(0x200B);
    td_ram.x200B[4] = 0;
    td_ram.x200F_len = 17;
    BAD(0x200F);
    td_ram.x200F_len = 3;
    DOM[0].capacity = 8; /* less than the descriptor's size */
    BAD(0x200F);
    DOM[0].data = NULL;
    BAD(0x200F);
    DOM[0].length = NULL;
    BAD(0x200F);
    /* persistence: offset and size within the group's struct */
    S[13].storage = ODG_S_PERSIST | (2u << 2);
    BAD(0x1017);
    S[13].offset = sizeof(td_persist_comm_t);
    BAD(0x1017);
    S[13].offset = sizeof(td_persist_comm_t) - 2u; /* the last two bytes: inside */
    CHECK_EQ(odg_verify(&D, &bad), ODG_OK);
    fresh();
    S[21].offset = sizeof(td_persist_comm_t); /* one byte past the end */
    BAD(0x1400);
    S[20].offset = sizeof(td_persist_comm_t); /* aligned, but beyond */
    BAD(0x1400);
    S[74].offset = sizeof(td_persist_app_t) - 8u; /* char[9]: its terminator is outside */
    BAD(0x2500);
    S[73].storage = ODG_S_PERSIST | (TD_GROUP_COMM << 2); /* offset 8 of an 8-byte group */
    BAD(0x2500);
    DOM[2].length = &td_ram.x200F_len; /* a persisted domain's length outside the group */
    BAD(0x2500);
    DOM[2].data = td_ram.x2300_s6_buf; /* and its buffer */
    BAD(0x2500);
    defaults = td_persist_app_defaults;
    defaults.x2500_s3 = 2000000; /* FLASH default outside the limits */
    G[1].defaults = &defaults;
    BAD(0x2500);
    G[1].defaults = NULL;
    BAD(0x2500);
    /* the runs of the defaults: in the mirror, in order, each of some bytes */
    G[1].spread = NULL;
    BAD(0x2500);
    G[1].spread = beyond;
    BAD(0x2500);
    G[1].spread = backwards;
    BAD(0x2500);
    G[1].spread = empty_run;
    BAD(0x2500);
    /* hook map */
    HM[1].sub_pos = 64;
    BAD(0x2300);
    HM[0].sub_pos = 63;
    BAD(0x2300);
    HM[2].kinds = 0;
    BAD(0x2300);
    HM[2].kinds = 8;
    BAD(0x2300);
    HM[5].sub_pos = 200;
    BAD(0xFFFF);
    D.n_hooks = 5;
    BAD(0xFFFF);
    S[28].attr |= ODG_A_HOOK;
    BAD(0xFFFF);
    D.hook_map = NULL;
    BAD(0xFFFF);
    /* groups */
    G[1].nv_addr = 10;
    BAD(0xFFFF);
    G[0].nv_addr = 0xFFFFFFF0u;
    BAD(0xFFFF);
    G[0].size = 0; /* first seen as 0x1017 lying outside its group */
    BAD(0x1017);
    G[0].mirror = NULL;
    BAD(0x1017);
    D.groups = NULL;
    BAD(0xFFFF);
    /* nothing left broken */
    CHECK_EQ(odg_verify(&D, &bad), ODG_OK);
    CHECK_EQ(odg_verify(&td, &bad), ODG_OK);
}

/* odg_group_defaults: every window of a mirror whose defaults are three runs, against the
 * mirror spelled out, with the bytes around the window untouched. */
static void test_group_defaults(void)
{
    static const uint16_t spread[8] = {2, 5, 9, 10, 20, 24, 0, 0};
    static const uint8_t runs[8] = {0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77, 0x88};
    static const uint8_t whole[26] = {0, 0, 0x11, 0x22, 0x33, 0, 0, 0, 0, 0x44, 0, 0, 0,
                                      0, 0, 0, 0, 0, 0, 0, 0x55, 0x66, 0x77, 0x88, 0, 0};
    odg_group_t g;
    uint8_t out[28];
    uint32_t from, n, i;
    memset(&g, 0, sizeof g);
    g.defaults = runs;
    g.spread = spread;
    g.size = sizeof whole;
    for (from = 0; from <= sizeof whole; from++) {
        for (n = 0; from + n <= sizeof whole; n++) {
            memset(out, 0xA5, sizeof out);
            odg_group_defaults(&g, from, n, out + 1);
            CHECK(out[0] == 0xA5u && out[n + 1u] == 0xA5u && memcmp(out + 1, whole + from, n) == 0);
        }
    }
    memset(out, 0xA5, sizeof out); /* odg_group_reset: the whole mirror, nothing around it */
    g.mirror = out + 1;
    odg_group_reset(&g);
    CHECK(out[0] == 0xA5u && out[sizeof whole + 1u] == 0xA5u && memcmp(out + 1, whole, sizeof whole) == 0);
    g.defaults = NULL; /* no run at all: every byte zero, and `defaults` is never read */
    g.spread = spread + 6;
    memset(out, 0xA5, sizeof out);
    odg_group_defaults(&g, 3, 4, out);
    for (i = 0; i < sizeof out; i++) {
        CHECK_EQ(out[i], i < 4u ? 0u : 0xA5u);
    }
}

/* Values are found through the dictionary's blocks, not at fixed addresses: a copy of td with
 * other ROM, RAM and group structs reads and writes those. */
static void test_blocks(void)
{
    static td_rom_t rom2;
    static td_ram_t ram2;
    static td_persist_comm_t comm2;
    static odg_group_t groups2[2];
    odg_dict_t d2 = td;
    odg_ref_t r;
    uint8_t b[16];
    uint32_t n = 0, x2007 = td_ram.x2007;
    rom2 = td_rom;
    rom2.x1000 = 0x0A0B0C0Du;
    ram2 = td_ram_defaults;
    ram2.x2007 = 0x11223344u;
    comm2 = td_persist_comm_defaults;
    comm2.x1017 = 0x0102;
    memcpy(groups2, td.groups, sizeof groups2);
    groups2[TD_GROUP_COMM].mirror = &comm2;
    d2.rom = &rom2;
    d2.ram = &ram2;
    d2.groups = groups2;
    CHECK_EQ(odg_verify(&d2, NULL), ODG_OK);
    CHECK_EQ(odg_find(&d2, 0x1000, 0, &r), ODG_OK);
    CHECK_EQ(odg_read(&r, 0, b, sizeof b, &n), ODG_OK);
    CHECK(n == 4 && bytes_eq(b, "\x0D\x0C\x0B\x0A", 4));
    CHECK_EQ(odg_find(&d2, 0x2007, 0, &r), ODG_OK);
    CHECK_EQ(odg_read(&r, 0, b, sizeof b, &n), ODG_OK);
    CHECK(n == 4 && bytes_eq(b, "\x44\x33\x22\x11", 4));
    CHECK_EQ(odg_write(&r, "\x01\x02\x03\x04", 4), ODG_OK);
    CHECK_EQ(ram2.x2007, 0x04030201u);
    CHECK_EQ(td_ram.x2007, x2007);
    CHECK_EQ(odg_find(&d2, 0x2009, 0, &r), ODG_OK);
    CHECK_EQ(odg_write(&r, "zz", 2), ODG_OK);
    CHECK(bytes_eq(ram2.x2009, "zz\0\0\0\0\0\0\0", 9));
    CHECK_EQ(odg_length(&r), 2);
    CHECK_EQ(odg_find(&d2, 0x200B, 0, &r), ODG_OK);
    CHECK_EQ(odg_write_part(&r, 0, "Q\0", 2, 4), ODG_OK);
    CHECK_EQ(odg_write_part(&r, 2, "R\0", 2, 4), ODG_OK);
    CHECK(ram2.x200B[0] == 'Q' && ram2.x200B[1] == 'R' && ram2.x200B[2] == 0);
    CHECK_EQ(odg_length(&r), 4);
    CHECK_EQ(odg_find(&d2, 0x1017, 0, &r), ODG_OK);
    CHECK_EQ(odg_read(&r, 0, b, sizeof b, &n), ODG_OK);
    CHECK(n == 2 && bytes_eq(b, "\x02\x01", 2));
    CHECK_EQ(odg_write(&r, "\x03\x04", 2), ODG_OK);
    CHECK_EQ(comm2.x1017, 0x0403);
    CHECK_EQ(td_persist_comm.x1017, 1000);
    CHECK_EQ(odg_find(&d2, 0x2200, 2, &r), ODG_OK); /* limits found by sub position */
    CHECK_EQ(odg_write(&r, "\xE9\x03\x00\x00", 4), ODG_ABORT_VALUE_HIGH);
    CHECK_EQ(odg_write(&r, "\xE8\x03\x00\x00", 4), ODG_OK);
    CHECK_EQ(ram2.x2200_s2, 1000);
}

/* -0.0 and +0.0 are the same number to the limits */
static void test_signed_zero(void)
{
    odg_ref_t r;
    uint8_t b[8];
    fresh();
    L[3].low = d2u(0.0);
    L[3].high = d2u(-0.0);
    CHECK_EQ(odg_find(&D, 0x2200, 4, &r), ODG_OK);
    le(b, d2u(-0.0), 8);
    CHECK_EQ(odg_write(&r, b, 8), ODG_OK);
    le(b, d2u(0.0), 8);
    CHECK_EQ(odg_write(&r, b, 8), ODG_OK);
    le(b, d2u(-1e-300), 8);
    CHECK_EQ(odg_write(&r, b, 8), ODG_ABORT_VALUE_LOW);
    le(b, d2u(1e-300), 8);
    CHECK_EQ(odg_write(&r, b, 8), ODG_ABORT_VALUE_HIGH);
    L[2].low = d2u(0.0);
    L[2].high = d2u(0.0);
    CHECK_EQ(odg_find(&D, 0x2200, 3, &r), ODG_OK);
    CHECK_EQ(odg_write(&r, "\x00\x00\x00\x80", 4), ODG_OK); /* REAL32 -0 */
    CHECK_EQ(odg_write(&r, "\x01\x00\x00\x80", 4), ODG_ABORT_VALUE_LOW);
    fresh();
    CHECK_EQ(odg_init(&td, NODE), ODG_OK);
}

/* ---- typed access and clients ------------------------------------------------------------ */

static unsigned hook_runs;

static odg_abort_t count_hook(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data,
                              uint32_t len, void *ctx)
{
    (void)ref, (void)kind, (void)data, (void)len, (void)ctx;
    hook_runs++;
    return ODG_ABORT_DATA_LOCAL; /* would veto an SDO write */
}

static void test_typed(void)
{
    uint8_t u8 = 0;
    uint16_t u16 = 0;
    uint32_t u32 = 0;
    int64_t i64 = 0;
    float r32 = 0.0f;
    uint32_t *p;
    CHECK_EQ(odg_init(&td, NODE), ODG_OK);
    /* get: the value in its C type, wherever it lives */
    CHECK_EQ(odg_get_u32(&td, 0x2007, 0, &u32), ODG_OK);
    CHECK_EQ(u32, 0x89ABCDEFu);
    CHECK_EQ(odg_get_u32(&td, 0x1000, 0, &u32), ODG_OK); /* ROM */
    CHECK_EQ(u32, td_rom.x1000);
    CHECK_EQ(odg_get_u16(&td, 0x1017, 0, &u16), ODG_OK); /* a persistence group's mirror */
    CHECK_EQ(u16, td_persist_comm.x1017);
    CHECK_EQ(odg_get_u32(&td, 0x2016, 0, &u32), ODG_OK); /* UNSIGNED24 lives in a uint32_t */
    CHECK_EQ(odg_get_u32(&td, 0x2400, 0, &u32), ODG_OK); /* write-only on the bus: still read */
    /* the C type must match: size, absent objects, strings, commands */
    CHECK_EQ(odg_get_u16(&td, 0x2007, 0, &u16), ODG_ABORT_TYPE_LENGTH);
    CHECK_EQ(odg_get_u8(&td, 0x2016, 0, &u8), ODG_ABORT_TYPE_LENGTH);
    CHECK_EQ(odg_get_u32(&td, 0x2009, 0, &u32), ODG_ABORT_TYPE_LENGTH); /* VISIBLE_STRING */
    CHECK_EQ(odg_get_u32(&td, 0x1010, 1, &u32), ODG_ABORT_TYPE_LENGTH); /* a command, no value */
    CHECK_EQ(odg_get_u32(&td, 0x6FFF, 0, &u32), ODG_ABORT_NO_OBJECT);
    CHECK_EQ(odg_get_u16(&td, 0x2100, 99, &u16), ODG_ABORT_NO_SUB);
    /* set: no access rights, limits or hooks (the application's own access) */
    CHECK_EQ(odg_set_u32(&td, 0x2401, 0, 0x1234u), ODG_OK); /* read-only on the bus */
    CHECK_EQ(td_ram.x2401, 0x1234u);
    CHECK_EQ(odg_set_u32(&td, 0x2200, 2, 0xFFFFFFFFu), ODG_OK); /* beyond its HighLimit */
    CHECK_EQ(td_ram.x2200_s2, 0xFFFFFFFFu);
    CHECK_EQ(odg_set_i64(&td, 0x2500, 3, -123456789012LL), ODG_OK);
    CHECK_EQ(odg_get_i64(&td, 0x2500, 3, &i64), ODG_OK);
    CHECK(i64 == -123456789012LL);
    CHECK_EQ(odg_set_r32(&td, 0x2008, 0, 1.5f), ODG_OK);
    CHECK_EQ(odg_get_r32(&td, 0x2008, 0, &r32), ODG_OK);
    CHECK(r32 == 1.5f);
    hook_runs = 0;
    CHECK_EQ(odg_hook_register(&td, 0x2300, 2, count_hook, NULL), ODG_OK);
    CHECK_EQ(odg_set_u16(&td, 0x2300, 2, 77), ODG_OK);
    CHECK_EQ(hook_runs, 0);
    CHECK_EQ(td_ram.x2300_s2, 77);
    CHECK_EQ(wr(0x2300, 2, "\x05\x00", 2), ODG_ABORT_DATA_LOCAL); /* an SDO write meets the hook */
    CHECK_EQ(hook_runs, 1);
    CHECK_EQ(odg_hook_register(&td, 0x2300, 2, NULL, NULL), ODG_OK);
    CHECK_EQ(odg_set_u32(&td, 0x1000, 0, 1u), ODG_ABORT_READ_ONLY); /* a constant */
    CHECK_EQ(odg_set_u8(&td, 0x2007, 0, 1u), ODG_ABORT_TYPE_LENGTH);
    /* ptr: the value itself, for hot paths; none for constants or another size */
    p = odg_ptr_u32(&td, 0x2007, 0);
    CHECK(p == &td_ram.x2007);
    *p = 42u;
    CHECK_EQ(odg_get_u32(&td, 0x2007, 0, &u32), ODG_OK);
    CHECK_EQ(u32, 42u);
    CHECK(odg_ptr_u16(&td, 0x1017, 0) == &td_persist_comm.x1017);
    CHECK(odg_ptr_u32(&td, 0x1000, 0) == NULL);
    CHECK(odg_ptr_u16(&td, 0x2007, 0) == NULL);
    CHECK(odg_ptr(&td, 0x6FFF, 0, 4) == NULL);
    CHECK_EQ(odg_init(&td, NODE), ODG_OK);
}

/* A client that records what it hears. */
typedef struct {
    odg_client_t client; /* first: the callbacks cast back */
    unsigned changes, commands, all;
    uint16_t last_index;
    uint8_t last_sub, restore;
    odg_abort_t answer;
} probe_t;

static void probe_changed(odg_client_t *self, const odg_ref_t *ref)
{
    probe_t *p = (probe_t *)(void *)self;
    p->changes++;
    if (ref == NULL) {
        p->all++;
    } else {
        p->last_index = ref->entry->index;
        p->last_sub = ref->sub->sub;
    }
}

static odg_abort_t probe_command(odg_client_t *self, const odg_dict_t *dict, uint8_t sub,
                                 int restore)
{
    probe_t *p = (probe_t *)(void *)self;
    (void)dict;
    p->commands++;
    p->last_sub = sub;
    p->restore = (uint8_t)restore;
    return p->answer;
}

static void test_clients(void)
{
    probe_t a, b;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    a.client.changed = probe_changed;
    b.client.changed = probe_changed;
    b.client.command = probe_command;
    CHECK_EQ(odg_init(&td, NODE), ODG_OK);
    /* without a client answering, 0x1010/0x1011 abort as without persistence */
    CHECK_EQ(wr(0x1010, 1, "save", 4), ODG_ABORT_DATA_STORE);
    odg_attach(&td, &a.client);
    odg_attach(&td, &a.client); /* once only */
    CHECK_EQ(wr(0x1010, 1, "save", 4), ODG_ABORT_DATA_STORE);
    CHECK_EQ(a.changes, 0);
    /* every writer reaches the client: SDO/PDO writes, the application, parts, odg_changed */
    CHECK_EQ(wr(0x2007, 0, "\x01\x02\x03\x04", 4), ODG_OK);
    CHECK_EQ(a.changes, 1);
    CHECK_EQ(a.last_index, 0x2007);
    CHECK_EQ(wr(0x2200, 2, "\xFF\xFF\xFF\xFF", 4), ODG_ABORT_VALUE_HIGH); /* refused: nothing changed */
    CHECK_EQ(a.changes, 1);
    CHECK_EQ(odg_set_u8(&td, 0x1400, 2, 0xFE), ODG_OK);
    CHECK_EQ(a.changes, 2);
    CHECK(a.last_index == 0x1400 && a.last_sub == 2);
    CHECK_EQ(odg_set_u32(&td, 0x1000, 0, 1u), ODG_ABORT_READ_ONLY);
    CHECK_EQ(a.changes, 2);
    CHECK_EQ(wr_part(0x2009, 0, 0, "ab", 2, 4), ODG_OK);
    CHECK_EQ(a.changes, 2); /* not complete yet */
    CHECK_EQ(wr_part(0x2009, 0, 2, "cd", 2, 4), ODG_OK);
    CHECK(a.changes == 3 && a.last_index == 0x2009);
    odg_changed(&td, NULL);
    CHECK(a.changes == 4 && a.all == 1);
    /* the first client with a command answers 0x1010/0x1011, after the command word */
    odg_attach(&td, &b.client);
    b.answer = ODG_OK;
    CHECK_EQ(wr(0x1010, 3, "save", 4), ODG_OK);
    CHECK(b.commands == 1 && b.last_sub == 3 && b.restore == 0);
    CHECK_EQ(wr(0x1011, 2, "load", 4), ODG_OK);
    CHECK(b.commands == 2 && b.last_sub == 2 && b.restore == 1);
    CHECK_EQ(wr(0x1011, 2, "save", 4), ODG_ABORT_DATA_STORE);
    CHECK_EQ(b.commands, 2);
    b.answer = ODG_ABORT_HARDWARE;
    CHECK_EQ(wr(0x1010, 1, "save", 4), ODG_ABORT_HARDWARE);
    CHECK_EQ(a.changes, 4); /* a command changes no value */
    CHECK_EQ(odg_set_u32(&td, 0x2007, 0, 9u), ODG_OK);
    CHECK(a.changes == 5 && b.changes == 1); /* both hear it */
    /* odg_init detaches them all */
    CHECK_EQ(odg_init(&td, NODE), ODG_OK);
    CHECK(td.state->clients == NULL);
    CHECK_EQ(odg_set_u32(&td, 0x2007, 0, 9u), ODG_OK);
    CHECK(a.changes == 5 && b.changes == 1);
    CHECK_EQ(wr(0x1010, 1, "save", 4), ODG_ABORT_DATA_STORE);
}

int main(void)
{
    test_abort_text();
    test_init();
    test_verify();
    test_group_defaults();
    test_blocks();
    test_find();
    test_reads();
    test_numeric_writes();
    test_string_writes();
    test_write_part();
    test_access();
    test_limits();
    test_hooks();
    test_node_id();
    test_mapping();
    test_signed_zero();
    test_typed();
    test_clients();
    CHECK_EQ(odg_init(&td, NODE), ODG_OK);
    CHECK_EQ(odg_verify(&td, NULL), ODG_OK);
    return done();
}
