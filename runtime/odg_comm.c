/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_comm.c - the communication values in force at boot, which reset communication brings
 * back (odg_comm.h). It calls no other file of the node.
 */
#include "odg_impl.h"
#include "odg_node.h"

/* What reset communication brings back: the numbers in 0x1000-0x1FFF an SDO client may write,
 * but not the error history 0x1003 (events, not parameters: comm_walk skips it) nor the commands
 * 0x1010/0x1011. */
static int comm_value(const odg_sub_t *s)
{
    uint32_t cls = ODG_S_CLASS(s->storage);
    return (s->attr & ODG_A_WRITE) != 0u && (cls == ODG_S_RAM || cls == ODG_S_PERSIST) &&
           !IS_STREAM(s); /* IS_STREAM: the stream types this build serves, all the dictionary has */
}

/* Bytes of the C type holding a number of wire size `size`: the copy keeps values as stored
 * (sizes above 4 only with the types wider than 32 bits). */
static uint32_t native_size(uint32_t size)
{
    return size == 3u ? 4u : (ODG_CFG_INT64 && size > 4u ? 8u : size);
}

/* One value and its place in node->comm (the bytes of its C type): COMM_KEEP copies the
 * dictionary's value there, COMM_BACK back; COMM_SAVED and COMM_LOADED act on the values of the
 * persistence groups 0x1010/0x1011 sub `sub` named (1: all), which the next boot would load:
 * the value saved, or the group's default. */
enum { COMM_KEEP, COMM_BACK, COMM_SAVED, COMM_LOADED };

static void comm_copy(odg_node_t *n, const odg_sub_t *s, uint32_t size, uint8_t *at, int how, uint8_t sub)
{
    const odg_dict_t *d = n->cfg.dict;
    const odg_group_t *g = ODG_S_CLASS(s->storage) == ODG_S_PERSIST ? &d->groups[ODG_S_GROUP(s->storage)] : NULL;
    uint8_t *value = odg_value_(d, s), *to = at;
    const uint8_t *from = value;
    if (how == COMM_BACK) {
        to = value;
        from = at;
    } else if (how != COMM_KEEP && (g == NULL || (sub != 1u && g->store_sub != sub))) {
        return; /* not of the groups named */
    } else if (how == COMM_LOADED) {
        odg_group_defaults(g, s->offset, size, at);
        if (s->attr & ODG_A_NODEID) { /* as odg_init adds it */
            odg_num_put_(at, size, odg_num_get_(at, size) + n->cfg.node_id);
        }
        return;
    }
    odg_copy(to, from, size);
}

/* The communication values of one object: their bytes, and with `n` (not NULL) each copied
 * to `at` in sub-index order. Sub-indices are looked up one by one (odg_find), so that an
 * object's elements are found however the dictionary describes them. */
static uint32_t comm_object(const odg_dict_t *d, odg_node_t *n, const odg_entry_t *en, uint8_t *at, int how,
                            uint8_t sub)
{
    uint8_t last = d->subs[en->first + en->count - 1u].sub, k = 0;
    uint32_t bytes = 0;
    odg_ref_t r;
    do {
        if (odg_find(d, en->index, k, &r) == ODG_OK && comm_value(r.sub)) {
            uint32_t size = native_size(r.sub->size);
            if (n != NULL) {
                comm_copy(n, r.sub, size, at + bytes, how, sub);
            }
            bytes += size;
        }
    } while (k++ < last);
    return bytes;
}

/* Walk the communication values, objects in index order while they fit whole into
 * node->comm (all of them for n == NULL, which only counts); returns the bytes they take. */
static uint32_t comm_walk(odg_node_t *n, const odg_dict_t *d, int how, uint8_t sub)
{
    uint32_t at = 0, size;
    uint16_t e;
    for (e = 0; e < d->n_entries && d->entries[e].index <= 0x1FFFu; e++) {
        const odg_entry_t *en = &d->entries[e];
        if (en->index < 0x1000u || en->index == 0x1003u) {
            continue; /* data type definitions, the error history */
        }
        size = comm_object(d, NULL, en, NULL, how, sub);
        if (n != NULL && at + size > ODG_NODE_COMM_BYTES) {
            break; /* the rest keep their values at reset communication (NODE.md) */
        }
        if (n != NULL) {
            (void)comm_object(d, n, en, &n->comm[at], how, sub);
        }
        at += size;
    }
    return at;
}

uint32_t odg_node_comm_bytes(const odg_dict_t *dict)
{
    return comm_walk(NULL, dict, COMM_KEEP, 0);
}

void odg_node_comm_keep(odg_node_t *node)
{
    (void)comm_walk(node, node->cfg.dict, COMM_KEEP, 0);
}

void odg_comm_stored_(odg_node_t *n, uint8_t sub, int restore)
{
    (void)comm_walk(n, n->cfg.dict, restore ? COMM_LOADED : COMM_SAVED, sub);
}

void odg_comm_back_(odg_node_t *n)
{
    (void)comm_walk(n, n->cfg.dict, COMM_BACK, 0);
}

