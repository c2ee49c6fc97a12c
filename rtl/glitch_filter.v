// glitch_filter: per-bit digital glitch filter (debouncer) for synchronised inputs.
//
// Each bit i keeps a counter.  While d[i] equals q[i] the counter is held at 0;
// while d[i] differs from q[i] it counts the consecutive differing samples, and
// on the L-th such sample q[i] takes d[i] (counter back to 0).  So q[i] changes
// only after d[i] has been stable at the new value for L clocks: a pulse of
// L-1 clocks never reaches q, a pulse of L clocks does (and then lasts L clocks).
//   L = (len == 0) ? FILTER_LEN : len       (run-time register, 0 = parameter)
// L = 1 is a plain one-register delay.  The input must already be synchronous
// (put sync_2ff in front of it).
//
// Ports:
//   clk, rst     clock, synchronous active-high reset
//   load         q <= d and all counters cleared (start-up / re-initialisation,
//                so that the first real level is not seen as an edge)
//   len          run-time filter length in clocks, 0 selects FILTER_LEN
//   d            synchronous input, WIDTH independent bits
//   q            filtered output (registered)
// Parameters:
//   WIDTH        number of independent bits
//   FILTER_LEN   default filter length in clocks (1 .. 2**LEN_W-1)
//   LEN_W        width of len and of each counter
//   RESET_VALUE  q after reset
// Latency: L clock cycles from a change of d to the change of q.
// Reset: q = RESET_VALUE, counters 0.
// FIXED = 1 (the length is always FILTER_LEN; len is ignored): each counter is an
// XNOR LFSR of FW bits (the least FW >= 2 with FILTER_LEN <= 2**FW - 1), started at 0
// and stepped where the binary counter increments; the L-th differing sample is the
// LFSR state FILTER_LEN - 1 steps after 0 (F_TERM; the states 0 .. FILTER_LEN - 1 steps
// are distinct, checked at elaboration), so q is the binary counter's clock for clock,
// without an incrementer or a magnitude compare (hall_decoder, irc_decoder).
// Resources: WIDTH * (LEN_W + 1) flip-flops (FIXED = 1: WIDTH * (FW + 1)), no DSP/BRAM.
`default_nettype none
module glitch_filter #(
    parameter integer WIDTH = 1,
    parameter integer FILTER_LEN = 4,
    parameter integer LEN_W = 8,
    parameter [WIDTH-1:0] RESET_VALUE = {WIDTH{1'b0}},
    parameter integer FIXED = 0           // 1: len ignored, the length is FILTER_LEN (LFSR counters)
) (
    input  wire             clk,
    input  wire             rst,
    input  wire             load,
    input  wire [LEN_W-1:0] len,
    input  wire [WIDTH-1:0] d,
    output wire [WIDTH-1:0] q
);
    localparam [LEN_W-1:0] DEF_LEN = FILTER_LEN[LEN_W-1:0];

    // ---- FIXED = 1: LFSR counters (XNOR feedback, maximal-length taps, all-zero start allowed) ----
    function integer lfsr_w;
        input integer l;
        begin
            lfsr_w = 2;
            while (lfsr_w < 16 && l > (1 << lfsr_w) - 1) lfsr_w = lfsr_w + 1;
        end
    endfunction
    localparam integer FW = lfsr_w(FILTER_LEN);
    // taps (bit positions, bit 0 = the newest) of the maximal-length sequences, FW = 2 .. 16
    function [15:0] lfsr_taps;
        input integer w;
        begin
            case (w)
                2: lfsr_taps = 16'h0003;  3: lfsr_taps = 16'h0006;  4: lfsr_taps = 16'h000c;
                5: lfsr_taps = 16'h0014;  6: lfsr_taps = 16'h0030;  7: lfsr_taps = 16'h0060;
                8: lfsr_taps = 16'h00b8;  9: lfsr_taps = 16'h0110; 10: lfsr_taps = 16'h0240;
               11: lfsr_taps = 16'h0500; 12: lfsr_taps = 16'h0829; 13: lfsr_taps = 16'h100d;
               14: lfsr_taps = 16'h2015; 15: lfsr_taps = 16'h6000; default: lfsr_taps = 16'hd008;
            endcase
        end
    endfunction
    localparam [15:0]   TAPS16 = lfsr_taps(FW);
    localparam [FW-1:0] TAPS = TAPS16[FW-1:0];
    function [FW-1:0] lfsr_step;
        input [FW-1:0] v;
        begin
            lfsr_step = {v[FW-2:0], ~(^(v & TAPS))};
        end
    endfunction
    // the state FILTER_LEN - 1 steps after 0, and the first step that reaches it (must be FILTER_LEN - 1)
    function [FW-1:0] lfsr_term;
        input integer l;
        integer j;
        begin
            lfsr_term = {FW{1'b0}};
            for (j = 1; j < l; j = j + 1) lfsr_term = lfsr_step(lfsr_term);
        end
    endfunction
    localparam [FW-1:0] F_TERM = lfsr_term(FILTER_LEN);
    function integer lfsr_first;
        input integer l;
        integer j;
        reg [FW-1:0] v;
        begin
            lfsr_first = -1;
            v = {FW{1'b0}};
            for (j = 0; j < l; j = j + 1) begin
                if (lfsr_first < 0 && v == F_TERM) lfsr_first = j;
                v = lfsr_step(v);
            end
        end
    endfunction

    genvar i;
    generate
    if (FIXED != 0) begin : g_fixed
        wire unused_len = &{1'b0, len};
        for (i = 0; i < WIDTH; i = i + 1) begin : g_bit
            reg              qr;
            reg  [FW-1:0]    cnt;
            always @(posedge clk) begin
                if (rst) begin
                    qr   <= RESET_VALUE[i];
                    cnt  <= {FW{1'b0}};
                end else if (load) begin
                    qr   <= d[i];
                    cnt  <= {FW{1'b0}};
                end else if (d[i] == qr) begin
                    cnt  <= {FW{1'b0}};
                end else if (cnt == F_TERM) begin
                    qr   <= d[i];
                    cnt  <= {FW{1'b0}};
                end else begin
                    cnt  <= lfsr_step(cnt);
                end
            end
            assign q[i] = qr;
        end
    end else begin : g_var
        wire [LEN_W-1:0] len_eff = (len == {LEN_W{1'b0}}) ? DEF_LEN : len;
        for (i = 0; i < WIDTH; i = i + 1) begin : g_bit
            reg              qr;
            reg  [LEN_W-1:0] cnt;
            wire [LEN_W:0]   cnt_inc = {1'b0, cnt} + {{LEN_W{1'b0}}, 1'b1};
            always @(posedge clk) begin
                if (rst) begin
                    qr   <= RESET_VALUE[i];
                    cnt  <= {LEN_W{1'b0}};
                end else if (load) begin
                    qr   <= d[i];
                    cnt  <= {LEN_W{1'b0}};
                end else if (d[i] == qr) begin
                    cnt  <= {LEN_W{1'b0}};
                end else if (cnt_inc >= {1'b0, len_eff}) begin
                    qr   <= d[i];
                    cnt  <= {LEN_W{1'b0}};
                end else begin
                    cnt  <= cnt_inc[LEN_W-1:0];
                end
            end
            assign q[i] = qr;
        end
    end
    endgenerate

`ifndef SYNTHESIS
    initial begin
        if (FILTER_LEN < 1 || FILTER_LEN >= (1 << LEN_W))
            $display("ERROR: glitch_filter FILTER_LEN=%0d out of range 1..%0d", FILTER_LEN, (1 << LEN_W) - 1);
        if (FIXED != 0 && lfsr_first(FILTER_LEN) != FILTER_LEN - 1)
            $display("ERROR: glitch_filter FIXED: LFSR of %0d bits repeats before %0d steps", FW, FILTER_LEN - 1);
    end
`endif
endmodule
`default_nettype wire
