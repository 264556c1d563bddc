/*
 * alltypes_hooks.c - the hook function that alltypes.toml names, for building the node
 * program (runtime/linux/odg_node_main.c) against the alltypes dictionary.
 */
#include "alltypes.h"

odg_abort_t alltypes_notice(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len,
                            void *ctx)
{
    (void)ref, (void)kind, (void)data, (void)len, (void)ctx;
    return ODG_OK;
}
