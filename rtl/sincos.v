// sincos: sin and cos of the 16-bit electrical angle (quarter-wave table + linear
// interpolation), fully pipelined, one angle per clock.
//
// Method (bit-exact model: gen/empc/rtlmodel/sincos.py):
//   q = angle[15:14], r = angle[13:0]; x = q[0] ? 2^14 - r : r  (0..2^14);
//   |sin| = T[k] + ((D[k] * f + 16) >> 5), k = x[13:5], f = x[4:0]   (x = 2^14 -> exactly 2^16)
//   T[k] = round(2^16 sin(k pi/1024)), D[k] = T[k+1] - T[k]  (512-word ROM, rtl/sincos_table.vh);
//   negative in quadrants 2, 3;  cos(angle) = sin(angle + 2^14).
//   The 8x5 interpolation product is built from shifts and adds (no DSP).
// Ports:
//   in_valid, angle   angle (unsigned ANGLE_BITS, 2^16 = 2 pi) sampled when in_valid = 1
//   out_valid         1-cycle pulse, LATENCY cycles after in_valid
//   sin_out, cos_out  signed TRIG_W (18), 1.0 = 2^TRIG_FRAC (2^16), range -65536..65536;
//                     updated only with out_valid, held otherwise. Nothing can saturate.
// Error: |out - round(2^16 sin)| <= 1 LSB and |out - 2^16 sin| < 1.0 LSB for all 65536 angles
//   (tested exhaustively, tb/test_sincos.py).
// Parameters: none (formats from empc_formats.vh; the table is generated for ANGLE_BITS = 16,
//   TRIG_FRAC = 16 and checked against the model by the test).
// Latency: 4 clock cycles (input regs, ROM read, interpolation, sign). Throughput 1/clock.
// Resources: 1 RAMB16 (512 x 25, dual read port), no DSP.
// Reset: all pipeline registers and outputs clear to 0 (the ROM read registers too); the ROM
//   contents are constant.
`default_nettype none
module sincos (
    input  wire                                   clk,
    input  wire                                   rst,
    input  wire                                   in_valid,
    input  wire [`EMPC_ANGLE_BITS-1:0]            angle,
    output reg                                    out_valid,
    output reg  signed [`EMPC_TRIG_W-1:0]         sin_out,
    output reg  signed [`EMPC_TRIG_W-1:0]         cos_out
);
`include "empc_formats.vh"
    localparam integer AW = `EMPC_ANGLE_BITS;          // 16
    localparam integer TW = `EMPC_TRIG_W;              // 18
    localparam integer QB = AW - 2;                    // 14: bits inside a quadrant
    localparam integer LB = 9;                         // 512 table nodes per quadrant
    localparam integer FB = QB - LB;                   // 5 interpolation bits
    localparam integer VB = `EMPC_TRIG_FRAC + 1;       // 17: node value 0..2^16
    localparam integer DB = 8;                         // node difference (max 201)
    localparam integer WB = VB + DB;                   // 25: ROM word
    localparam integer PB = DB + FB;                   // 13: interpolation product
    localparam [VB-1:0] ONE = {1'b1, {(VB-1){1'b0}}};  // 2^16
    localparam [AW-1:0] QUARTER = {2'b01, {QB{1'b0}}}; // 2^14 = pi/2

    // quarter-wave ROM: word k = {T[k], D[k]}
    reg [WB-1:0] rom [0:(1<<LB)-1];
    initial begin
`include "sincos_table.vh"
    end

    // D * f by shift-and-add (kept out of the DSP48A1 on purpose)
    function [PB-1:0] mul_df;
        input [DB-1:0] d;
        input [FB-1:0] f;
        integer i;
        begin
            mul_df = {PB{1'b0}};
            for (i = 0; i < FB; i = i + 1)
                if (f[i]) mul_df = mul_df + ({{FB{1'b0}}, d} << i);
        end
    endfunction

    // ---- stage A: quadrant folding -------------------------------------------------
    wire [AW-1:0] ang_c = angle + QUARTER;             // cos = sin(angle + pi/2), modulo 2 pi
    wire [QB:0]   x_s   = angle[QB]   ? ({1'b1, {QB{1'b0}}} - {1'b0, angle[QB-1:0]}) : {1'b0, angle[QB-1:0]};
    wire [QB:0]   x_c   = ang_c[QB]   ? ({1'b1, {QB{1'b0}}} - {1'b0, ang_c[QB-1:0]}) : {1'b0, ang_c[QB-1:0]};

    reg [LB-1:0] a_addr_s, a_addr_c;
    reg [FB-1:0] a_f_s, a_f_c;
    reg          a_full_s, a_full_c, a_neg_s, a_neg_c, a_v;
    always @(posedge clk) begin
        if (rst) begin
            a_addr_s <= {LB{1'b0}}; a_addr_c <= {LB{1'b0}};
            a_f_s    <= {FB{1'b0}}; a_f_c    <= {FB{1'b0}};
            a_full_s <= 1'b0;       a_full_c <= 1'b0;
            a_neg_s  <= 1'b0;       a_neg_c  <= 1'b0;
            a_v      <= 1'b0;
        end else begin
            a_addr_s <= x_s[QB-1:FB]; a_addr_c <= x_c[QB-1:FB];
            a_f_s    <= x_s[FB-1:0];  a_f_c    <= x_c[FB-1:0];
            a_full_s <= x_s[QB];      a_full_c <= x_c[QB];
            a_neg_s  <= angle[AW-1];  a_neg_c  <= ang_c[AW-1];
            a_v      <= in_valid;
        end
    end

    // ---- stage B: ROM read (synchronous, both ports of one block RAM) -------------
    reg [WB-1:0] b_word_s, b_word_c;
    reg [FB-1:0] b_f_s, b_f_c;
    reg          b_full_s, b_full_c, b_neg_s, b_neg_c, b_v;
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
            b_f_s    <= {FB{1'b0}}; b_f_c    <= {FB{1'b0}};
            b_full_s <= 1'b0;       b_full_c <= 1'b0;
            b_neg_s  <= 1'b0;       b_neg_c  <= 1'b0;
            b_v      <= 1'b0;
        end else begin
            b_f_s    <= a_f_s;    b_f_c    <= a_f_c;
            b_full_s <= a_full_s; b_full_c <= a_full_c;
            b_neg_s  <= a_neg_s;  b_neg_c  <= a_neg_c;
            b_v      <= a_v;
        end
    end

    // ---- stage C: interpolation, round half up -------------------------------------
    wire [PB-1:0] p_s = mul_df(b_word_s[DB-1:0], b_f_s) + {{(PB-FB){1'b0}}, 1'b1, {(FB-1){1'b0}}};
    wire [PB-1:0] p_c = mul_df(b_word_c[DB-1:0], b_f_c) + {{(PB-FB){1'b0}}, 1'b1, {(FB-1){1'b0}}};
    wire [VB-1:0] m_s = b_word_s[WB-1:DB] + {{(VB-DB){1'b0}}, p_s[PB-1:FB]};
    wire [VB-1:0] m_c = b_word_c[WB-1:DB] + {{(VB-DB){1'b0}}, p_c[PB-1:FB]};

    reg [VB-1:0] c_mag_s, c_mag_c;
    reg          c_neg_s, c_neg_c, c_v;
    always @(posedge clk) begin
        if (rst) begin
            c_mag_s <= {VB{1'b0}}; c_mag_c <= {VB{1'b0}};
            c_neg_s <= 1'b0;       c_neg_c <= 1'b0;
            c_v     <= 1'b0;
        end else begin
            c_mag_s <= b_full_s ? ONE : m_s;
            c_mag_c <= b_full_c ? ONE : m_c;
            c_neg_s <= b_neg_s;    c_neg_c <= b_neg_c;
            c_v     <= b_v;
        end
    end

    // ---- stage D: sign ----------------------------------------------------------------
    wire signed [TW-1:0] mag_s = $signed({{(TW-VB){1'b0}}, c_mag_s});
    wire signed [TW-1:0] mag_c = $signed({{(TW-VB){1'b0}}, c_mag_c});
    always @(posedge clk) begin
        if (rst) begin
            out_valid <= 1'b0;
            sin_out   <= {TW{1'b0}};
            cos_out   <= {TW{1'b0}};
        end else begin
            out_valid <= c_v;
            if (c_v) begin
                sin_out <= c_neg_s ? -mag_s : mag_s;
                cos_out <= c_neg_c ? -mag_c : mag_c;
            end
        end
    end
endmodule
`default_nettype wire
