// park_core: 2-D rotation by the angle given as (sin, cos) on ONE time-shared
// registered multiplier (one DSP48A1); the datapath of park and inv_park.
//
//   INVERSE = 0 (Park, eq. 33):         y0 =  c x0 + s x1,  y1 = -s x0 + c x1
//   INVERSE = 1 (inverse Park, eq. 34): y0 =  c x0 - s x1,  y1 =  s x0 + c x1
//   each output: the exact sum of two W x TW products, rounded once (round half up,
//   (sum + 2^(TF-1)) >>> TF) and saturated to W bits.
//   Bit-exact model: gen/empc/rtlmodel/park.py (rotate()).
// Ports:
//   start            1-cycle request; x0, x1, sin_in, cos_in are sampled in that cycle.
//                    Ignored while busy.
//   x0, x1           signed W-bit data (format-neutral: output format = input format)
//   sin_in, cos_in   signed TW-bit, 1.0 = 2^TF (from sincos)
//   busy             high from the cycle after an accepted start up to the cycle before done
//                    (a start in the done cycle is accepted)
//   done             1-cycle pulse: y0, y1, sat updated in this cycle (held until the next done)
//   y0, y1           signed W-bit results
//   sat              1-cycle pulse with done if y0 or y1 saturated
// Parameters: W (data, <= 18), TW (trig, <= 18), TF (trig fraction bits), INVERSE (0/1).
// Latency: done is high LATENCY = 8 cycles after the start cycle (4 multiplier issues,
//   product, accumulate, round/saturate). Throughput: one rotation per 8 cycles.
// Resources: 1 DSP48A1 (registered A/B inputs, registered product), ~140 LUT, ~180 FF.
// Reset: all registers clear to 0 (outputs 0, not busy); a rotation in flight is dropped.
`default_nettype none
`include "empc_formats.vh"
module park_core #(
    parameter integer W       = `EMPC_I_W,
    parameter integer TW      = `EMPC_TRIG_W,
    parameter integer TF      = `EMPC_TRIG_FRAC,
    parameter integer INVERSE = 0
) (
    input  wire                 clk,
    input  wire                 rst,
    input  wire                 start,
    input  wire signed [W-1:0]  x0,
    input  wire signed [W-1:0]  x1,
    input  wire signed [TW-1:0] sin_in,
    input  wire signed [TW-1:0] cos_in,
    output reg                  busy,
    output reg                  done,
    output reg  signed [W-1:0]  y0,
    output reg  signed [W-1:0]  y1,
    output reg                  sat
);
    localparam integer PW = W + TW;          // product width
    localparam integer AW = PW + 1;          // sum of two products
    localparam integer RW = AW - TF;         // rounded sum
    localparam signed [W-1:0]  YMAX = {1'b0, {(W-1){1'b1}}};
    localparam signed [W-1:0]  YMIN = {1'b1, {(W-1){1'b0}}};

    // ---- operand latch and issue sequencer -------------------------------------
    reg signed [W-1:0]  r_x0, r_x1;
    reg signed [TW-1:0] r_s, r_c;
    reg                 issuing;
    reg [1:0]           step;                // product k = step: k0 c*x0, k1 s*x1, k2 s*x0, k3 c*x1

    // ---- multiplier (DSP48A1: A, B and product registers) -----------------------
    reg signed [W-1:0]  mul_a;
    reg signed [TW-1:0] mul_b;
    reg signed [PW-1:0] mul_p;
    // control travelling with the products: valid, first of a pair, subtract, second output
    reg c1_v, c1_first, c1_sub, c1_dst;
    reg c2_v, c2_first, c2_sub, c2_dst;
    reg c3_v, c3_last, c3_dst;

    reg signed [AW-1:0] acc;
    reg signed [W-1:0]  t0;                  // y0 waiting for y1
    reg                 t0_sat;

    wire signed [AW-1:0] p_ext  = {{(AW-PW){mul_p[PW-1]}}, mul_p};
    wire signed [AW-1:0] base   = c2_first ? {AW{1'b0}} : acc;
    // base +/- p as one adder: base + (p ^ -sub) + sub
    wire signed [AW-1:0] p_x    = p_ext ^ {AW{c2_sub}};
    // round half up: (acc + 2^(TF-1)) >>> TF computed as ((acc >>> (TF-1)) + 1) >>> 1,
    // the TF-1 bits below the rounding bit cannot carry and are dropped
    /* verilator lint_off UNUSEDSIGNAL */  // rsum[0] is below the result LSB
    wire signed [RW:0]   rsum   = acc[AW-1:TF-1] + {{RW{1'b0}}, 1'b1};
    /* verilator lint_on UNUSEDSIGNAL */
    wire signed [RW-1:0] rshift = rsum[RW:1];
    // out of range iff the bits from the W-1 up are not all equal (no comparator needed)
    wire                 r_ovf  = ~(&rshift[RW-1:W-1] | ~|rshift[RW-1:W-1]);
    wire                 r_hi   = r_ovf & ~rshift[RW-1];
    wire                 r_lo   = r_ovf &  rshift[RW-1];
    wire signed [W-1:0]  r_sat  = r_hi ? YMAX : r_lo ? YMIN : rshift[W-1:0];

    wire k_sub = (INVERSE != 0) ? (step == 2'd1) : (step == 2'd2);

    always @(posedge clk) begin
        if (rst) begin
            r_x0 <= {W{1'b0}}; r_x1 <= {W{1'b0}};
            r_s  <= {TW{1'b0}}; r_c <= {TW{1'b0}};
            issuing <= 1'b0; step <= 2'd0; busy <= 1'b0;
            mul_a <= {W{1'b0}}; mul_b <= {TW{1'b0}}; mul_p <= {PW{1'b0}};
            c1_v <= 1'b0; c1_first <= 1'b0; c1_sub <= 1'b0; c1_dst <= 1'b0;
            c2_v <= 1'b0; c2_first <= 1'b0; c2_sub <= 1'b0; c2_dst <= 1'b0;
            c3_v <= 1'b0; c3_last <= 1'b0; c3_dst <= 1'b0;
            acc <= {AW{1'b0}}; t0 <= {W{1'b0}}; t0_sat <= 1'b0;
            y0 <= {W{1'b0}}; y1 <= {W{1'b0}}; done <= 1'b0; sat <= 1'b0;
        end else begin
            done <= 1'b0;
            sat  <= 1'b0;
            // accept
            if (start && !busy) begin
                r_x0 <= x0; r_x1 <= x1; r_s <= sin_in; r_c <= cos_in;
                busy <= 1'b1; issuing <= 1'b1; step <= 2'd0;
            end
            // issue product `step`
            c1_v <= issuing;
            if (issuing) begin
                mul_a    <= step[0] ? r_x1 : r_x0;
                mul_b    <= (step[0] ^ step[1]) ? r_s : r_c;
                c1_first <= ~step[0];
                c1_sub   <= k_sub;
                c1_dst   <= step[1];
                step     <= step + 2'd1;
                if (step == 2'd3) issuing <= 1'b0;
            end
            // product
            mul_p <= mul_a * mul_b;
            c2_v <= c1_v; c2_first <= c1_first; c2_sub <= c1_sub; c2_dst <= c1_dst;
            // accumulate
            if (c2_v) acc <= base + p_x + {{(AW-1){1'b0}}, c2_sub};
            c3_v <= c2_v; c3_last <= ~c2_first; c3_dst <= c2_dst;
            // round, saturate, output
            if (c3_v && c3_last) begin
                if (!c3_dst) begin
                    t0 <= r_sat; t0_sat <= r_hi | r_lo;
                end else begin
                    y0 <= t0; y1 <= r_sat;
                    sat <= t0_sat | r_hi | r_lo;
                    done <= 1'b1;
                    busy <= 1'b0;
                end
            end
        end
    end
endmodule
`default_nettype wire
