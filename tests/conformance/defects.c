/*
 * defects.c - a node program that misbehaves on purpose, to prove `odgen conformance` notices.
 *
 * Built into the node program as its application (-DODG_APP) with -DODG_DEFECT=N: at start it
 * puts itself between the node and the bus, and changes or drops the frames the node sends in
 * one way per check family, as a faulty node would (tests/test_conformance.py).
 *
 * From ALLOWED_ERROR_AT_BOOT on, the behaviours are ones CiA 301 allows though odgen's own node
 * does not show them: the battery must pass (or skip) them, never fail.
 */
#include <string.h>

#include "odg_app.h"

#ifndef ODG_DEFECT
#error "define ODG_DEFECT (1..21)"
#endif

enum {
    SDO_VALUE = 1,    /* uploads of 0x1001.. return a changed value */
    SDO_LIMIT,        /* a value beyond a limit is accepted */
    ACCESS_READ_ONLY, /* a write to a read-only entry aborts with the wrong code */
    NMT_STATE,        /* the heartbeat says operational when stopped */
    HEARTBEAT_PERIOD, /* every second heartbeat is lost */
    PDO_DATA,         /* TPDOs carry other data than the mapped values */
    EMCY_LOST,        /* no EMCY frame reaches the bus */
    STORE_SIGNATURE,  /* a wrong 0x1010/0x1011 signature is accepted */
    SYNC_COUNTER,     /* the SYNC counter does not count */
    HB_CONSUMER_EMCY, /* a heartbeat timeout is reported with the wrong EMCY code */
    EMCY_TWICE,       /* every EMCY goes out twice, the inhibit time ignored */
    GUARD_TOGGLE,     /* the node guarding answer's toggle bit never changes */
    REGISTER_STALE,   /* the error reset EMCY still says generic and communication error */
    COMM_KEPT,        /* reset communication keeps the communication values written since boot */
    SDO_SERVER_COB,   /* an upload of 0x1200 says bit 31: the server it answers on is not valid */
    LSS_IDENTITY,     /* the LSS answer to "inquire serial number" is not 0x1018 sub 4 */
    SYNC_LATE,        /* TPDOs go out 20 ms late, past a SYNC window of 10 ms */
    WRONG_REFUSAL,    /* 0x06090030 ("value range exceeded") is answered as 0x08000000 instead */
    /* allowed behaviours */
    ALLOWED_ERROR_AT_BOOT,   /* an error history entry and a manufacturer error active from every boot;
                                0x1003 sub-entries beyond the errors recorded answer 0x08000024 */
    ALLOWED_PREOP_ON_ERROR,  /* a communication error active from every boot keeps the node out of
                                operational (as 0x1029 sub 1 = 0 allows) */
    ALLOWED_NO_SYNC_PRODUCER /* 0x1005 bit 30 refused with 0x06090030: the node cannot produce SYNC */
};

static odg_send_fn real_send;
static void *real_ctx;
static odg_node_t *the_node;
static uint8_t node_id;
static unsigned heartbeats;
static odg_frame_t held; /* SYNC_LATE: a TPDO held back, for held_ms so far */
static uint32_t held_ms;
static int holding;
static int booted; /* a boot-up went out: the errors "from every boot" are raised again */

static uint32_t abort_code(const odg_frame_t *f)
{
    return (uint32_t)f->data[4] | (uint32_t)f->data[5] << 8 | (uint32_t)f->data[6] << 16 |
           (uint32_t)f->data[7] << 24;
}

static void set_code(odg_frame_t *f, uint32_t code)
{
    f->data[4] = (uint8_t)code;
    f->data[5] = (uint8_t)(code >> 8);
    f->data[6] = (uint8_t)(code >> 16);
    f->data[7] = (uint8_t)(code >> 24);
}

/* An SDO abort with one of `codes` becomes a download response (success). */
static void accept_instead(odg_frame_t *f, uint32_t a, uint32_t b)
{
    uint32_t code = abort_code(f);
    if (f->data[0] == 0x80u && (code == a || code == b)) {
        f->data[0] = 0x60u;
        set_code(f, 0);
    }
}

/* ALLOWED_NO_SYNC_PRODUCER: a write that set 0x1005 bit 30 is undone and answered 0x06090030. */
static void refuse_sync_producer(odg_frame_t *f)
{
    odg_ref_t ref;
    uint8_t b[4] = {0u, 0u, 0u, 0u};
    uint32_t got = 0;
    if (f->data[0] != 0x60u || f->data[1] != 0x05u || f->data[2] != 0x10u ||
        odg_find(the_node->cfg.dict, 0x1005u, 0, &ref) != ODG_OK ||
        odg_read(&ref, 0, b, sizeof b, &got) != ODG_OK || got != 4u || !(b[3] & 0x40u)) {
        return;
    }
    b[3] &= (uint8_t)~0x40u;
    (void)odg_write(&ref, b, sizeof b);
    f->data[0] = 0x80u;
    set_code(f, 0x06090030u);
}

/* Returns 0 to drop the frame. */
static int mangle(odg_frame_t *f)
{
    uint32_t id = f->id;
    int sdo = id == 0x580u + node_id, hb = id == 0x700u + node_id;
    uint16_t index = (uint16_t)(f->data[1] | f->data[2] << 8);
    switch (ODG_DEFECT) {
    case SDO_VALUE:
        if (sdo && (f->data[0] & 0xE3u) == 0x43u && index > 0x1000u) {
            f->data[4] ^= 0x01u;
        }
        break;
    case SDO_LIMIT:
        if (sdo) {
            accept_instead(f, 0x06090031u, 0x06090032u);
        }
        break;
    case ACCESS_READ_ONLY:
        if (sdo && f->data[0] == 0x80u && abort_code(f) == 0x06010002u) {
            set_code(f, 0x08000000u);
        }
        break;
    case NMT_STATE:
        if (hb && f->data[0] == 0x04u) {
            f->data[0] = 0x05u;
        }
        break;
    case HEARTBEAT_PERIOD:
        return !(hb && f->data[0] != 0u && (heartbeats++ & 1u));
    case PDO_DATA:
        if (id >= 0x181u && id <= 0x4FFu && (id & 0x7Fu) == node_id && f->len > 0u) {
            f->data[0] ^= 0xFFu;
        }
        break;
    case EMCY_LOST:
        return !(id == 0x80u + node_id);
    case STORE_SIGNATURE:
        if (sdo) {
            accept_instead(f, 0x08000020u, 0x08000020u);
        }
        break;
    case SYNC_COUNTER:
        if (id == 0x80u && f->len == 1u) {
            f->data[0] = 1u;
        }
        break;
    case HB_CONSUMER_EMCY:
        if (id == 0x80u + node_id && f->data[0] == 0x30u && f->data[1] == 0x81u) {
            f->data[0] = 0x00u;
        }
        break;
    case EMCY_TWICE:
        if (id == 0x80u + node_id) {
            (void)real_send(real_ctx, f);
        }
        break;
    case GUARD_TOGGLE:
        if (hb) {
            f->data[0] &= 0x7Fu;
        }
        break;
    case REGISTER_STALE:
        if (id == 0x80u + node_id && f->data[0] == 0u && f->data[1] == 0u) {
            f->data[2] = 0x11u;
        }
        break;
    case SYNC_LATE:
        if (id >= 0x181u && id <= 0x4FFu && (id & 0x7Fu) == node_id && !holding) {
            held = *f;
            held_ms = 0;
            holding = 1;
            return 0;
        }
        break;
    case LSS_IDENTITY:
        if (id == 0x7E4u && f->data[0] == 0x5Du) {
            f->data[1] ^= 0x01u;
        }
        break;
    case SDO_SERVER_COB:
        if (sdo && (f->data[0] & 0xE3u) == 0x43u && index == 0x1200u) {
            f->data[7] |= 0x80u;
        }
        break;
    case WRONG_REFUSAL:
        if (sdo && f->data[0] == 0x80u && abort_code(f) == 0x06090030u) {
            set_code(f, 0x08000000u);
        }
        break;
    case ALLOWED_NO_SYNC_PRODUCER:
        if (sdo) {
            refuse_sync_producer(f);
        }
        break;
    case ALLOWED_ERROR_AT_BOOT:
        if (sdo && (f->data[0] & 0xE3u) == 0x43u && index == 0x1003u && f->data[3] != 0u &&
            abort_code(f) == 0u) { /* an empty slot: "no data available" */
            f->data[0] = 0x80u;
            set_code(f, 0x08000024u);
        }
        break;
    default:
        break;
    }
    return 1;
}

static int defect_send(void *ctx, const odg_frame_t *frame)
{
    odg_frame_t f;
    (void)ctx;
    if (ODG_DEFECT == COMM_KEPT) { /* before each answer, so also after each SDO write */
        odg_node_comm_keep(the_node); /* the values of now are the ones reset communication restores */
    }
    memcpy(&f, frame, sizeof f);
    if (f.id == 0x700u + node_id && f.len == 1u && f.data[0] == 0u) {
        booted = 1;
    }
    return mangle(&f) ? real_send(real_ctx, &f) : 0;
}

/* The errors of the allowed behaviours, raised at every boot (a reset of the node clears them). */
static void raise_errors(odg_node_t *node)
{
    if (ODG_DEFECT == ALLOWED_ERROR_AT_BOOT) {
        (void)odg_node_error_set(node, 0x5000u, 0, NULL, 0); /* device hardware: gone again, */
        (void)odg_node_error_clear(node, 0x5000u);          /* but in the history */
        (void)odg_node_error_set(node, 0xFF01u, 0, NULL, 0); /* manufacturer-specific: active */
    } else if (ODG_DEFECT == ALLOWED_PREOP_ON_ERROR) {
        (void)odg_node_error_set(node, 0x8110u, 0, NULL, 0); /* CAN overrun: a communication error */
    }
}

void odg_app_init(odg_node_t *node)
{
    real_send = node->cfg.send;
    real_ctx = node->cfg.send_ctx;
    node_id = node->cfg.node_id;
    the_node = node;
    node->cfg.send = defect_send;
    node->cfg.send_ctx = NULL;
    raise_errors(node);
    booted = 0;
}

void odg_app_tick(odg_node_t *node, uint32_t elapsed_ms)
{
    if (booted) {
        booted = 0;
        raise_errors(node);
    }
    if (ODG_DEFECT == ALLOWED_PREOP_ON_ERROR && odg_node_state(node) == ODG_NMT_OPERATIONAL) {
        odg_frame_t preop = {0, 2, 0, {0x80u, 0u, 0u, 0u, 0u, 0u, 0u, 0u}}; /* as the NMT master would */
        preop.data[1] = node_id;
        odg_node_receive(node, &preop);
    }
    if (ODG_DEFECT == SYNC_LATE && holding && (held_ms += elapsed_ms) >= 20u) {
        holding = 0;
        (void)real_send(real_ctx, &held);
    }
}
