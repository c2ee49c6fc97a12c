// sincos: sin and cos of the 16-bit electrical angle (quarter-wave table + linear
// interpolation), fully pipelined, one angle per clock.
//
// Method (bit-exact model: gen/empc/rtlmodel/sincos.py):
//   q = angle[15:14], r = angle[13:0]; x = q[0] ? 2^14 - r : r  (0..2^14);
//   |sin| = T[k] + ((D[k] * f + 16) >> 5), x = 32 k + f; for odd quadrants k = ~r[13:5],
//   f = ~r[4:0] + 1 (1..32), which equals x = 2^14 - r without a subtractor
//   T[k] = round(2^16 sin(k pi/1024)), D[k] = T[k+1] - T[k]  (512-word ROM, rtl/sincos_table.vh);
//   negative in quadrants 2, 3;  cos(angle) = sin(angle + 2^14).
//   The 8x6 interpolation product is a balanced shift-and-add tree (no DSP).
// Ports:
//   in_valid, angle   angle (unsigned ANGLE_BITS, 2^16 = 2 pi) sampled when in_valid = 1
//   out_valid         1-cycle pulse, LATENCY cycles after in_valid
//   sin_out, cos_out  signed TRIG_W (18), 1.0 = 2^TRIG_FRAC (2^16), range -65536..65536;
//                     updated only with out_valid, held otherwise. Nothing can saturate.
// Error: |out - round(2^16 sin)| <= 1 LSB and |out - 2^16 sin| < 1.0 LSB for all 65536 angles
//   (tested exhaustively, tb/test_sincos.py).
// Parameters: none (formats from empc_formats.vh; the table is generated for ANGLE_BITS = 16,
//   TRIG_FRAC = 16 and checked against the model by the test).
// Latency: 4 clock cycles (folding, ROM read, interpolation increment, add + sign).
//   Throughput 1/clock.
// Resources: 1 RAMB16 (512 x 25, dual read port), no DSP.
// Reset: all pipeline registers and outputs clear to 0 (the ROM read registers too); the ROM
//   contents are constant.
`default_nettype none
`include "empc_formats.vh"
module sincos (
    input  wire                                   clk,
    input  wire                                   rst,
    input  wire                                   in_valid,
    input  wire [`EMPC_ANGLE_BITS-1:0]            angle,
    output reg                                    out_valid,
    output reg  signed [`EMPC_TRIG_W-1:0]         sin_out,
    output reg  signed [`EMPC_TRIG_W-1:0]         cos_out
);
    localparam integer AW = `EMPC_ANGLE_BITS;          // 16
    localparam integer TW = `EMPC_TRIG_W;              // 18
    localparam integer QB = AW - 2;                    // 14: bits inside a quadrant
    localparam integer LB = 9;                         // 512 table nodes per quadrant
    localparam integer FB = QB - LB;                   // 5 interpolation bits
    localparam integer VB = `EMPC_TRIG_FRAC + 1;       // 17: node value 0..2^16
    localparam integer DB = 8;                         // node difference (max 201)
    localparam integer WB = VB + DB;                   // 25: ROM word
    localparam integer PB = DB + FB + 1;               // 14: interpolation product D*f + 16, f <= 32

    // quarter-wave ROM: word k = {T[k], D[k]}
    reg [WB-1:0] rom [0:(1<<LB)-1];
    initial begin
`include "sincos_table.vh"
    end

    // rounded interpolation increment (D * f + 16) >> 5, D * f by shift-and-add as a balanced
    // adder tree (kept out of the DSP48A1 on purpose); f = 0..32, and f = 32 (the only value
    // with bit FB set) has no other bit set, so its term shares the f[FB-1] term's adder input
    function [PB-FB-1:0] interp;
        input [DB-1:0] d;
        input [FB:0]   f;
        /* verilator lint_off UNUSEDSIGNAL */  // sum[FB-1:0] is below the rounded result
        reg   [PB-1:0] t0, t1, t2, t3, t4, sum;
        /* verilator lint_on UNUSEDSIGNAL */
        begin
            t0  = f[0] ? {{(FB+1){1'b0}}, d}      : {PB{1'b0}};
            t1  = f[1] ? {{FB{1'b0}}, d, 1'b0}    : {PB{1'b0}};
            t2  = f[2] ? {{(FB-1){1'b0}}, d, 2'b0} : {PB{1'b0}};
            t3  = f[3] ? {{(FB-2){1'b0}}, d, 3'b0} : {PB{1'b0}};
            t4  = f[4] ? {{(FB-3){1'b0}}, d, 4'b0} : f[5] ? {1'b0, d, 5'b0} : {PB{1'b0}};
            sum = ((t0 + t1) + (t2 + t3)) + (t4 + {{(PB-FB){1'b0}}, 1'b1, {(FB-1){1'b0}}});
            interp = sum[PB-1:FB];
        end
    endfunction

    // ---- stage A: quadrant folding -------------------------------------------------
    // Odd quadrants need S(2^14 - r) = S(~r + 1): table index ~r[13:5] and fraction
    // ~r[4:0] + 1 (1..32; 32 lands exactly on the next node), so no subtractor is needed.
    // cos(angle) = sin(angle + 2^14): same r, quadrant + 1.
    wire          odd_s = angle[QB];
    wire          odd_c = ~angle[QB];
    wire [QB-1:0] rr_s  = angle[QB-1:0] ^ {QB{odd_s}};
    wire [QB-1:0] rr_c  = angle[QB-1:0] ^ {QB{odd_c}};

    reg [LB-1:0] a_addr_s, a_addr_c;
    reg [FB:0]   a_f_s, a_f_c;
    reg          a_neg_s, a_neg_c, a_v;
    always @(posedge clk) begin
        if (rst) begin
            a_addr_s <= {LB{1'b0}}; a_addr_c <= {LB{1'b0}};
            a_f_s    <= {(FB+1){1'b0}}; a_f_c <= {(FB+1){1'b0}};
            a_neg_s  <= 1'b0;       a_neg_c  <= 1'b0;
            a_v      <= 1'b0;
        end else begin
            a_addr_s <= rr_s[QB-1:FB]; a_addr_c <= rr_c[QB-1:FB];
            a_f_s    <= {1'b0, rr_s[FB-1:0]} + {{FB{1'b0}}, odd_s};
            a_f_c    <= {1'b0, rr_c[FB-1:0]} + {{FB{1'b0}}, odd_c};
            a_neg_s  <= angle[AW-1];
            a_neg_c  <= angle[AW-1] ^ angle[AW-2];
            a_v      <= in_valid;
        end
    end

    // ---- stage B: ROM read (synchronous, both ports of one block RAM) -------------
    reg [WB-1:0] b_word_s, b_word_c;
    reg [FB:0]   b_f_s, b_f_c;
    reg          b_neg_s, b_neg_c, b_v;
    always @(posedge clk) begin
        if (rst) begin
            b_word_s <= {WB{1'b0}};
            b_word_c <= {WB{1'b0}};
        end else begin
            b_word_s <= rom[a_addr_s];
            b_word_c <= rom[a_addr_c];
        end
    end
    always @(posedge clk) begin
        if (rst) begin
            b_f_s   <= {(FB+1){1'b0}}; b_f_c <= {(FB+1){1'b0}};
            b_neg_s <= 1'b0;       b_neg_c <= 1'b0;
            b_v     <= 1'b0;
        end else begin
            b_f_s   <= a_f_s;      b_f_c   <= a_f_c;
            b_neg_s <= a_neg_s;    b_neg_c <= a_neg_c;
            b_v     <= a_v;
        end
    end

    // ---- stage C: rounded interpolation increment ------------------------------------
    reg [VB-1:0]    c_t_s, c_t_c;
    reg [PB-FB-1:0] c_q_s, c_q_c;
    reg             c_neg_s, c_neg_c, c_v;
    wire [PB-FB-1:0] q_s = interp(b_word_s[DB-1:0], b_f_s);
    wire [PB-FB-1:0] q_c = interp(b_word_c[DB-1:0], b_f_c);
    always @(posedge clk) begin
        if (rst) begin
            c_t_s   <= {VB{1'b0}};      c_t_c <= {VB{1'b0}};
            c_q_s   <= {(PB-FB){1'b0}}; c_q_c <= {(PB-FB){1'b0}};
            c_neg_s <= 1'b0;            c_neg_c <= 1'b0;
            c_v     <= 1'b0;
        end else begin
            c_t_s   <= b_word_s[WB-1:DB];  c_t_c <= b_word_c[WB-1:DB];
            c_q_s   <= q_s;                c_q_c <= q_c;
            c_neg_s <= b_neg_s;            c_neg_c <= b_neg_c;
            c_v     <= b_v;
        end
    end

    // ---- stage D: T + increment, sign -------------------------------------------------
    wire [VB-1:0] m_s = c_t_s + {{(VB-(PB-FB)){1'b0}}, c_q_s};
    wire [VB-1:0] m_c = c_t_c + {{(VB-(PB-FB)){1'b0}}, c_q_c};
    // conditional negation as (m ^ -neg) + neg: one carry chain per output
    wire [TW-1:0] sgn_s = ({{(TW-VB){1'b0}}, m_s} ^ {TW{c_neg_s}}) + {{(TW-1){1'b0}}, c_neg_s};
    wire [TW-1:0] sgn_c = ({{(TW-VB){1'b0}}, m_c} ^ {TW{c_neg_c}}) + {{(TW-1){1'b0}}, c_neg_c};
    always @(posedge clk) begin
        if (rst) begin
            out_valid <= 1'b0;
            sin_out   <= {TW{1'b0}};
            cos_out   <= {TW{1'b0}};
        end else begin
            out_valid <= c_v;
            if (c_v) begin
                sin_out <= $signed(sgn_s);
                cos_out <= $signed(sgn_c);
            end
        end
    end
endmodule
`default_nettype wire
