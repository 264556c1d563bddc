/*
 * test_lss_master.c - the LSS master (runtime/odg_lss_master.c) against simulated LSS slaves
 * written from CiA 305: fastscan finds each slave without node-id in turn, whatever the order
 * and delay of their answers, the services are answered or refused, and silence is a timeout.
 */
#include <string.h>

#include "check.h"
#include "odg_lss_master.h"

#define N_SLAVES 4u

typedef struct slave {
    uint32_t id[4];
    uint8_t node_id;  /* 0xFF: none */
    uint8_t mode;     /* 0 waiting, 1 configuration */
    uint8_t lss_sub;  /* fastscan: the part it answers for next */
    uint8_t sel;      /* switch selective: parts matched */
    uint8_t present;
    uint8_t store_error;
} slave_t;

static slave_t slaves[N_SLAVES];
static odg_frame_t queue[64]; /* the slaves' answers, delivered by the test */
static unsigned n_queue;
static unsigned delay_ticks; /* ms before the answers arrive */

static void reply(uint8_t cs, uint8_t b1)
{
    odg_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = ODG_LSS_SLAVE_COB;
    f.len = 8;
    f.data[0] = cs;
    f.data[1] = b1;
    if (n_queue < 64u) {
        queue[n_queue++] = f;
    }
}

static uint32_t le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static void slave_hears(slave_t *s, const uint8_t *d)
{
    uint32_t v = le32(d + 1);
    uint8_t bit = d[5], sub = d[6], next = d[7];
    if (!s->present) {
        return;
    }
    switch (d[0]) {
    case 0x04:
        s->mode = d[1];
        break;
    case 0x40: case 0x41: case 0x42: case 0x43:
        s->sel = (uint8_t)(s->id[d[0] - 0x40u] == v && s->sel == d[0] - 0x40u ? s->sel + 1u : 0u);
        if (s->sel == 4u) {
            s->mode = 1;
            s->sel = 0;
            reply(0x44, 0);
        }
        break;
    case 0x11:
        if (s->mode == 1u) {
            s->node_id = d[1];
            reply(0x11, 0);
        }
        break;
    case 0x17:
        if (s->mode == 1u) {
            reply(0x17, s->store_error);
        }
        break;
    case 0x5E:
        if (s->mode == 1u) {
            reply(0x5E, s->node_id);
        }
        break;
    case 0x51:
        if (s->node_id != 0xFFu || s->mode != 0u) {
            break;
        }
        if (bit == 0x80u) {
            s->lss_sub = 0;
            reply(0x4F, 0);
        } else if (bit <= 31u && sub == s->lss_sub && ((v ^ s->id[sub]) >> bit) == 0u) {
            reply(0x4F, 0);
            if (bit == 0u) {
                s->lss_sub = next;
                if (next < sub) {
                    s->mode = 1;
                }
            }
        }
        break;
    default:
        break;
    }
}

static int to_slaves(void *ctx, const odg_frame_t *f)
{
    unsigned i;
    (void)ctx;
    if (f->id == ODG_LSS_MASTER_COB && f->len == 8u) {
        for (i = 0; i < N_SLAVES; i++) {
            slave_hears(&slaves[i], f->data);
        }
    }
    return 0;
}

/* Run until the service ends: the answers arrive delay_ticks ms after the question. */
static unsigned run(odg_lssm_t *m)
{
    unsigned ms = 0, waited = 0, i;
    while (m->state == ODG_LSSM_BUSY && ms < 100000u) {
        if (n_queue > 0u && waited >= delay_ticks) {
            odg_frame_t q[64];
            unsigned n = n_queue;
            memcpy(q, queue, n * sizeof q[0]);
            n_queue = 0;
            waited = 0;
            for (i = 0; i < n; i++) {
                CHECK_EQ(odg_lssm_receive(m, &q[i]), 1);
            }
        } else {
            waited = n_queue > 0u ? waited + 1u : 0u;
            odg_lssm_tick(m, 1);
            ms++;
        }
    }
    return ms;
}

static void setup(void)
{
    static const uint32_t ids[N_SLAVES][4] = {
        {0x000004D2, 0x00010203, 0x00020001, 0x5EA1C0DE},
        {0x000004D2, 0x00010203, 0x00020001, 0x5EA1C0DC}, /* differs in the serial's low bits */
        {0x00000001, 0xFFFFFFFF, 0x00000000, 0x00000000},
        {0x80000000, 0x00000000, 0xFFFFFFFF, 0x00000001},
    };
    unsigned i;
    memset(slaves, 0, sizeof slaves);
    for (i = 0; i < N_SLAVES; i++) {
        memcpy(slaves[i].id, ids[i], sizeof ids[i]);
        slaves[i].node_id = 0xFF;
        slaves[i].present = 1;
    }
    n_queue = 0;
}

static int find_in_config_mode(void)
{
    unsigned i;
    int found = -1;
    for (i = 0; i < N_SLAVES; i++) {
        if (slaves[i].mode == 1u) {
            CHECK_EQ(found, -1); /* only one */
            found = (int)i;
        }
    }
    return found;
}

/* Fastscan, node-id, back to waiting: every slave gets one, lowest identity first. */
static void test_fastscan_all(unsigned delay)
{
    static const unsigned order[N_SLAVES] = {2, 1, 0, 3};
    odg_lssm_t m;
    unsigned k;
    int s;
    setup();
    delay_ticks = delay;
    odg_lssm_init(&m, to_slaves, NULL, 10);
    for (k = 0; k < N_SLAVES; k++) {
        CHECK_EQ(odg_lssm_fastscan(&m), ODG_OK);
        CHECK_EQ(odg_lssm_fastscan(&m), ODG_ABORT_DATA_STATE);
        (void)run(&m);
        CHECK_EQ_AT(m.state, ODG_LSSM_DONE, k);
        s = find_in_config_mode();
        CHECK_EQ_AT(s, (int)order[k], k);
        if (s < 0) {
            return;
        }
        CHECK(memcmp(m.identity, slaves[s].id, sizeof m.identity) == 0);
        CHECK_EQ(odg_lssm_configure_node_id(&m, (uint8_t)(10u + k)), ODG_OK);
        (void)run(&m);
        CHECK_EQ(m.state, ODG_LSSM_DONE);
        CHECK_EQ(slaves[s].node_id, 10u + k);
        CHECK_EQ(odg_lssm_inquire_node_id(&m), ODG_OK);
        (void)run(&m);
        CHECK_EQ(m.value, 10u + k);
        CHECK_EQ(odg_lssm_switch_global(&m, ODG_LSS_WAITING), ODG_OK);
        CHECK_EQ(m.state, ODG_LSSM_DONE);
    }
    CHECK_EQ(odg_lssm_fastscan(&m), ODG_OK); /* nobody left without a node-id */
    CHECK_EQ(run(&m), 10);
    CHECK_EQ(m.state, ODG_LSSM_NO_ANSWER);
}

static void test_services(void)
{
    odg_lssm_t m;
    setup();
    delay_ticks = 0;
    odg_lssm_init(&m, to_slaves, NULL, 0);
    CHECK_EQ(m.timeout_ms, ODG_LSSM_TIMEOUT_MS);
    CHECK_EQ(odg_lssm_switch_selective(&m, slaves[1].id), ODG_OK);
    (void)run(&m);
    CHECK_EQ(m.state, ODG_LSSM_DONE);
    CHECK_EQ(find_in_config_mode(), 1);
    slaves[1].store_error = 2;
    CHECK_EQ(odg_lssm_store(&m), ODG_OK);
    (void)run(&m);
    CHECK_EQ(m.state, ODG_LSSM_REFUSED);
    CHECK_EQ(m.error, 2);
    CHECK_EQ(odg_lssm_switch_global(&m, ODG_LSS_WAITING), ODG_OK);
    CHECK_EQ(odg_lssm_store(&m), ODG_OK); /* nobody in configuration mode: silence */
    CHECK_EQ(run(&m), ODG_LSSM_TIMEOUT_MS);
    CHECK_EQ(m.state, ODG_LSSM_NO_ANSWER);
    setup();
    slaves[0].present = slaves[1].present = slaves[2].present = slaves[3].present = 0;
    CHECK_EQ(odg_lssm_fastscan(&m), ODG_OK);
    (void)run(&m);
    CHECK_EQ(m.state, ODG_LSSM_NO_ANSWER);
}

/* Parts of the identity known: each takes one question; the slave found is the one that has them. */
static void test_fastscan_known(void)
{
    odg_lssm_t m;
    uint32_t want[4];
    unsigned ms;
    setup();
    delay_ticks = 0;
    odg_lssm_init(&m, to_slaves, NULL, 10);
    memcpy(want, slaves[0].id, sizeof want);
    CHECK_EQ(odg_lssm_fastscan_known(&m, want, 0x0F), ODG_OK); /* all four: 5 questions */
    ms = run(&m);
    CHECK_EQ(m.state, ODG_LSSM_DONE);
    CHECK_EQ(ms, 5u * 10u);
    CHECK_EQ(find_in_config_mode(), 0);
    CHECK(memcmp(m.identity, slaves[0].id, sizeof m.identity) == 0);
    setup();
    CHECK_EQ(odg_lssm_fastscan_known(&m, want, 0x07), ODG_OK); /* the serial searched: slave 1 is lower */
    ms = run(&m);
    CHECK_EQ(m.state, ODG_LSSM_DONE);
    CHECK_EQ(ms, (4u + 33u) * 10u);
    CHECK_EQ(find_in_config_mode(), 1);
    CHECK_EQ(m.identity[3], slaves[1].id[3]);
    setup();
    want[1] = 0x0BAD;
    CHECK_EQ(odg_lssm_fastscan_known(&m, want, 0x03), ODG_OK); /* nobody has that product code */
    (void)run(&m);
    CHECK_EQ(m.state, ODG_LSSM_NO_ANSWER);
    CHECK_EQ(find_in_config_mode(), -1);
}

int main(void)
{
    test_fastscan_all(0);
    test_fastscan_all(7); /* answers late in each question's time */
    test_services();
    test_fastscan_known();
    return done();
}
