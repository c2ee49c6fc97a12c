// irc_decoder: incremental encoder (IRC) interface for one axis.
//
// A, B, index and mark pins -> sync_2ff -> glitch_filter -> x4 quadrature
// decoder -> POS_W-bit position counter, plus index/mark position latches and
// an illegal-transition monitor.
//
// Quadrature: the Gray phase g = {B, A^B} runs 0,1,2,3 for the sequence
// AB = 00,10,11,01 (A leads B): that direction counts UP.  Per filtered sample
// the phase step (g - g_prev) mod 4 is 0 (no change), 1 (+1), 3 (-1) or 2:
// both A and B changed in one sample = illegal transition.  An illegal
// transition never changes the count: err_pulse for one clock, sticky
// err_flag, saturating err_cnt (the direction of such a step is unknown, so
// the count is left alone and the error is reported; re-align via the index).
//
// Position: pos is a modular counter, it wraps modulo 2**POS_W by design
// (+2**31-1 -> -2**31 and back).  Consumers must use differences
// (pos_a - pos_b computed modulo 2**POS_W is exact for any movement below
// 2**(POS_W-1) counts), never compare absolute values across a wrap.  There is
// no preset input on purpose: pos_sense and the speed estimate rely on every
// change of pos being a real movement.
//
// Index / mark: on the rising edge of the filtered index, index_pos takes the
// position of that same sample (the count after this sample's step),
// index_event pulses for one clock and index_seen is set (sticky; cleared by
// index_clear, a set in the same clock wins).  index_dir is the direction
// (dir) at that edge.  The mark input has identical logic (mark_*).  Note: the
// index latches on its rising edge in both directions of motion, so the
// latched value of a w-count wide index pulse differs by w between the two
// directions of approach.
//
// Ports:
//   clk, rst                        clock, synchronous active-high reset
//   irc_a, irc_b, irc_index, irc_mark   asynchronous pins (synchronised here)
//   filt_len[LEN_W]                 run-time glitch-filter length, 0 = FILTER_LEN
//   err_clear                       clears err_flag and err_cnt (an error in
//                                   the same clock still counts: set wins)
//   index_clear, mark_clear         clear index_seen / mark_seen
//   pos[POS_W]                      position counter (signed, modular)
//   dir                             direction of the last counted step, 1 = up
//   index_pos, index_seen, index_event, index_dir
//   mark_pos,  mark_seen,  mark_event
//   err_pulse, err_flag, err_cnt[ERR_W]   illegal-transition monitor
//   in_state[4]                     filtered {mark, index, B, A}
//   ready                           1 once the start-up sequence is done
// Parameters:
//   POS_W        counter width (default `EMPC_POS_W = 32)
//   FILTER_LEN   default glitch-filter length in clocks (1..2**LEN_W-1)
//   LEN_W        width of filt_len
//   FILT_FIXED   1: filt_len ignored, the length is always FILTER_LEN (glitch_filter FIXED:
//                LFSR counters, the same outputs; axis_periph, which ties filt_len to 0)
//   ERR_W        width of the saturating error counter
//   SYNC_STAGES  synchroniser depth
// Latency: pin -> pos / events: SYNC_STAGES + L + 1 clocks (L = filter length).
//   Max count rate: one count per L clocks (each filtered level lasts >= L).
// Start-up: after reset the synchronisers fill (SYNC_STAGES clocks), the
//   filters load the synchronised levels (no filtering delay), and one clock
//   later the decoder takes them as its previous state; ready rises
//   SYNC_STAGES + 2 clocks after reset.  Levels present at start-up are thus
//   never counted and an index that is high at start-up is not an event.
// Reset: pos = 0, all latches, flags and counters 0.
// Resources: ~ 3*POS_W + 4*(LEN_W+1) + ERR_W + 20 flip-flops, no DSP/BRAM.
`default_nettype none
`include "empc_formats.vh"
module irc_decoder #(
    parameter integer POS_W = `EMPC_POS_W,
    parameter integer FILTER_LEN = 8,
    parameter integer LEN_W = 8,
    parameter integer ERR_W = 16,
    parameter integer SYNC_STAGES = 2,
    parameter integer FILT_FIXED = 0      // 1: filt_len ignored, the filters' length is FILTER_LEN (LFSR counters)
) (
    input  wire             clk,
    input  wire             rst,
    input  wire             irc_a,
    input  wire             irc_b,
    input  wire             irc_index,
    input  wire             irc_mark,
    input  wire [LEN_W-1:0] filt_len,
    input  wire             err_clear,
    input  wire             index_clear,
    input  wire             mark_clear,
    output reg  [POS_W-1:0] pos,
    output reg              dir,
    output reg  [POS_W-1:0] index_pos,
    output reg              index_seen,
    output reg              index_event,
    output reg              index_dir,
    output reg  [POS_W-1:0] mark_pos,
    output reg              mark_seen,
    output reg              mark_event,
    output reg              err_pulse,
    output reg              err_flag,
    output reg  [ERR_W-1:0] err_cnt,
    output wire [3:0]       in_state,
    output reg              ready
);
    // ---------------- synchroniser + glitch filter ----------------
    wire [3:0] pins = {irc_mark, irc_index, irc_b, irc_a};
    wire [3:0] synced;
    wire [3:0] filt;

    sync_2ff #(.WIDTH(4), .STAGES(SYNC_STAGES)) u_sync (
        .clk(clk), .rst(rst), .d(pins), .q(synced)
    );

    // start-up sequencer: a shift register of ones (flip-flops instead of a counter and its
    // compares): init_ge[j] = 1 from the j-th clock after reset on; the filters load in
    // clock SYNC_STAGES, ready rises in clock SYNC_STAGES + 2
    reg  [SYNC_STAGES:0]   init_sh;
    wire [SYNC_STAGES+1:0] init_ge = {init_sh, 1'b1};
    wire filt_load = init_ge[SYNC_STAGES] && !init_ge[SYNC_STAGES+1];

    glitch_filter #(.WIDTH(4), .FILTER_LEN(FILTER_LEN), .LEN_W(LEN_W), .FIXED(FILT_FIXED)) u_filt (
        .clk(clk), .rst(rst), .load(filt_load), .len(filt_len), .d(synced), .q(filt)
    );
    assign in_state = filt;

    // ---------------- decoder ----------------
    reg [3:0] prev;   // filtered state of the previous sample

    wire [1:0] g_now  = {filt[1], filt[1] ^ filt[0]};
    wire [1:0] g_prev = {prev[1], prev[1] ^ prev[0]};
    wire [1:0] g_step = g_now - g_prev;
    wire step_up   = ready && (g_step == 2'd1);
    wire step_dn   = ready && (g_step == 2'd3);
    wire step_bad  = ready && (g_step == 2'd2);
    wire index_edge = ready && filt[2] && !prev[2];
    wire mark_edge  = ready && filt[3] && !prev[3];

    // one adder, +1 / -1 / 0 (no multiplexer after the carry chain)
    wire [POS_W-1:0] pos_next = pos + {{(POS_W-1){step_dn}}, step_up | step_dn};
    wire dir_next = step_up ? 1'b1 : step_dn ? 1'b0 : dir;
    // saturating error counter: the incrementer's carry out is err_cnt == all ones
    wire [ERR_W:0] err_p1 = {1'b0, err_cnt} + {{ERR_W{1'b0}}, 1'b1};

    always @(posedge clk) begin
        if (rst) begin
            init_sh     <= {(SYNC_STAGES+1){1'b0}};
            ready       <= 1'b0;
            prev        <= 4'b0000;
            pos         <= {POS_W{1'b0}};
            dir         <= 1'b0;
            index_pos   <= {POS_W{1'b0}};
            index_seen  <= 1'b0;
            index_event <= 1'b0;
            index_dir   <= 1'b0;
            mark_pos    <= {POS_W{1'b0}};
            mark_seen   <= 1'b0;
            mark_event  <= 1'b0;
            err_pulse   <= 1'b0;
            err_flag    <= 1'b0;
            err_cnt     <= {ERR_W{1'b0}};
        end else begin
            init_sh <= init_ge[SYNC_STAGES:0];
            ready   <= init_sh[SYNC_STAGES];
            prev <= filt;
            pos  <= pos_next;
            dir  <= dir_next;

            index_event <= index_edge;
            if (index_edge) begin
                index_pos <= pos_next;
                index_dir <= dir_next;
            end
            index_seen <= index_edge | (index_seen & ~index_clear);

            mark_event <= mark_edge;
            if (mark_edge) mark_pos <= pos_next;
            mark_seen <= mark_edge | (mark_seen & ~mark_clear);

            err_pulse <= step_bad;
            err_flag  <= step_bad | (err_flag & ~err_clear);
            if (err_clear)
                err_cnt <= {{(ERR_W-1){1'b0}}, step_bad};
            else if (step_bad && !err_p1[ERR_W])
                err_cnt <= err_p1[ERR_W-1:0];
        end
    end
endmodule
`default_nettype wire
