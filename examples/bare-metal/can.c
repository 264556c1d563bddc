/*
 * can.c - the CAN driver of the node.
 *
 * The node is not reentrant: every odg_node_* call comes from the main loop. The receive
 * interrupt only moves frames from the controller's FIFO into a queue (a ring of CAN_RX_QUEUE
 * frames with one writer on each index: the interrupt moves `head`, the main loop `tail`, both
 * aligned 32-bit words, so neither needs the interrupts off); can_poll hands them to
 * odg_node_receive in order. Size the queue for the frames that arrive while the main loop is
 * busy elsewhere, the longest being a 0x1010 save (docs/porting.md). A full queue drops the
 * frame and the node sends EMCY 0x8110 (CAN overrun).
 *
 * The status interrupt only notes that the error state changed; can_poll reads it and tells
 * the node (error passive: EMCY 0x8120; bus-off: 0x1029's reaction; recovery: EMCY 0x8140).
 */
#include "can.h"

#include <string.h>

#include "board.h"

#define CAN_RX_QUEUE 32u /* a power of two */

static board_can_frame_t rx_queue[CAN_RX_QUEUE];
static volatile uint32_t rx_head;        /* frames queued: the interrupt's */
static volatile uint32_t rx_tail;        /* frames handed to the node: the main loop's */
static volatile uint8_t rx_lost;         /* set by the interrupt, cleared by the main loop */
static volatile uint8_t state_changed;   /* likewise */

void CAN_RX_IRQHandler(void)
{
    board_can_frame_t frame;
    while (board_can_receive(&frame)) {
        uint32_t head = rx_head;
        if (head - rx_tail == CAN_RX_QUEUE) {
            rx_lost = 1; /* full: this frame is lost */
            continue;
        }
        rx_queue[head % CAN_RX_QUEUE] = frame;
        __asm__ volatile("dmb" : : : "memory"); /* the frame is in place before head says so */
        rx_head = head + 1u;
    }
}

void CAN_SCE_IRQHandler(void)
{
    state_changed = 1; /* and clear the controller's status interrupt flags */
}

int can_send(void *ctx, const odg_frame_t *frame)
{
    board_can_frame_t f;
    (void)ctx;
    f.id = frame->id;
    f.len = frame->len;
    f.rtr = (uint8_t)((frame->flags & ODG_FRAME_RTR) != 0u);
    memcpy(f.data, frame->data, sizeof f.data);
    /* All mailboxes busy: the frame is dropped (a block upload resumes at the next tick). A
     * firmware that must not drop PDOs under load puts a software queue here. */
    return board_can_transmit(&f);
}

/* Take a flag an interrupt sets: read and clear it with the interrupts off, or a setting
 * between the two would be lost. */
static uint8_t take(volatile uint8_t *flag)
{
    uint32_t irq = board_irq_save();
    uint8_t was = *flag;
    *flag = 0;
    board_irq_restore(irq);
    return was;
}

void can_poll(odg_node_t *node)
{
    uint32_t tail = rx_tail;
    odg_frame_t f;
    while (tail != rx_head) {
        const board_can_frame_t *q = &rx_queue[tail % CAN_RX_QUEUE];
        __asm__ volatile("dmb" : : : "memory"); /* read the frame after the head that announced it */
        f.id = q->id;
        f.len = q->len;
        f.flags = q->rtr ? ODG_FRAME_RTR : 0u;
        memcpy(f.data, q->data, sizeof f.data);
        rx_tail = ++tail; /* the slot is free again */
        odg_node_receive(node, &f);
    }
    if (take(&rx_lost)) {
        odg_node_can_state(node, ODG_CAN_RX_OVERRUN);
    }
    if (take(&state_changed)) {
        odg_node_can_state(node, (odg_can_state_t)board_can_error_state());
    }
}
