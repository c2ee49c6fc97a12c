// mpc_lane: one row (d or q) of the explicit MPC law: polynomial gain and MAC.
//
// Per column (one per clock, bit-exact to gen/empc/rtlmodel/mpc_core.py, step 4):
//   h    = sat18(p1 + rshift_round(p2 * wn, 17))          mul1 (post-adder: + p1 2^17 + 2^16)
//   k    = sat18(p0 + rshift_round(h * wn, 17))           mul2 (post-adder: + p0 2^17 + 2^16)
//   term = sat48((k * a) << s);  acc = sat48(acc + term)  mul3 + fabric shift/accumulator
// The per-gain shift s (0..15) sits between the product and the accumulation, so the
// DSP48A1's accumulator cannot be used: shift (two 4:1 stages) and the 48-bit adder are
// fabric logic.  Both saturations avoid multiplexers: a saturated term is the AMAX pattern
// (flip-flop set / reset, low fill) with AMIN = AMAX + carry-in; a saturated accumulator
// holds AMAX (set / reset) with a flag for AMIN (carry-in on the next addition).
// Round step (rnd): mul3 = 2^23 (post-adder only), acc = sat48(acc + 2^23), after which du = acc[47:24] =
//   sat24(rshift_round(acc, ACC_FRAC - U_FRAC)) (flag f_du if that step saturated).
// Limiter support (sequenced by mpc_core): mul3 multiplies u18 (register loaded from the
// operand bus, u_ld) by the operand bus (m3_u), optionally accumulated (acc_x, shift 0);
// m3_rnd adds 2^17 - 1 for u18 < 0, so u_lim = prod3 >>> 17 = trunc0(u18 f / 2^17) (u = u_lim << 4);
// with m3_ur as well, mul3 = (ur >>> 4) << 17 instead and u_lim = ur[UW-1:VSH]: the limiter's output
// multiplexer u = lim ? scaled : u_raw is mul3 (m3_ur = !lim; the caller takes u[3:0] from ur).
// m2_t (lane d): mul2 = t * wn (the core loads u_max into wn) with no post-add.
// Timing (G1 = cycle in which cv, p2 and p1 are valid): p0 valid in G1+2, a (operand bus)
// in G1+4, s in G1+6; acc includes the column from G1+8 (rnd: asserted in G1+4 of the
// step after the last column, when mul3 would sample its operands; s must read 0 in G1+6).
// mul products appear 2 cycles after their operands.
// Ports: see the port list; f_* are sticky saturation flags (cleared by clr); f_or sets f_term,
// f_acc, f_du as well (the core chains the other lane's flags in: one clock later, long before done).
// Parameters: none (widths from empc_formats.vh).
// Reset / clr: flags clear to 0; clr / acc_clr make the next accumulation start from 0
// (the acc register itself resets to AMAX, a don't-care value).
`default_nettype none
`include "empc_formats.vh"
module mpc_lane (
    input  wire                            clk,
    input  wire                            rst,
    input  wire                            clr,       // start of an update: acc = 0, flags = 0
    input  wire signed [`EMPC_OPW-1:0]     wn,        // scheduling speed Q1.17
    input  wire                            cv,        // column valid (cycle G1)
    input  wire signed [`EMPC_OPW-1:0]     p2,        // G1
    input  wire signed [`EMPC_OPW-1:0]     p1,        // G1
    input  wire signed [`EMPC_OPW-1:0]     p0,        // G1+2
    input  wire signed [`EMPC_OPW-1:0]     a,         // G1+4 operand bus
    input  wire signed [`EMPC_OPW-1:0]     a_next,    // operand bus of the next cycle
    input  wire [`EMPC_PROD_SHIFT_BITS-1:0] s,        // G1+6 product shift
    input  wire                            rnd,       // round step (G1+4 of the extra step)
    input  wire                            acc_clr,   // acc = 0
    input  wire                            acc_x,     // acc += prod3 of two cycles ago (shift 0)
    input  wire                            m2_t,      // mul2 = t * wn, no post-add
    input  wire signed [`EMPC_OPW-1:0]     t,
    input  wire                            u_ld,      // u18 = a_next
    input  wire                            m3_u,      // mul3 = u18 * a
    input  wire                            m3_rnd,    // mul3 post-add 2^17 - 1 if u18 < 0
    input  wire                            m3_ur,     // mul3 = 0 * 0 + ((ur >>> 4) << 17) instead (with m3_rnd)
    input  wire signed [`EMPC_U_W-1:0]     ur,        // u_raw
    output wire signed [`EMPC_ACCW-1:0]    prod2,     // mul2 result
    output reg  signed [`EMPC_ACCW-1:0]    acc,
    output wire signed [`EMPC_U_W-`EMPC_U_FRAC+`EMPC_V_FRAC-1:0] u_lim,  // prod3 >>> 17 (m3_rnd + 2): see m3_ur
    output reg                             f_gain,
    output reg                             f_term,
    output reg                             f_acc,
    output reg                             f_du,
    input  wire [2:0]                      f_or       // {f_du, f_acc, f_term} of the other lane: ORed in
);
    localparam integer OPW  = `EMPC_OPW;                 // 18
    localparam integer PW   = 2 * OPW;                   // 36 product
    localparam integer ACCW = `EMPC_ACCW;                // 48
    localparam integer UW   = `EMPC_U_W;                 // 24
    localparam integer DSH  = `EMPC_ACC_FRAC - `EMPC_U_FRAC;   // 24
    localparam integer VSH  = `EMPC_U_FRAC - `EMPC_V_FRAC;     // 4
    localparam integer FR   = OPW - 1;                   // 17: Q1.17 scaling
    localparam integer TAW  = PW + 3;                    // 39: product << s[1:0]
    localparam signed [OPW-1:0]  OMAX = {1'b0, {(OPW-1){1'b1}}};
    localparam signed [OPW-1:0]  OMIN = {1'b1, {(OPW-1){1'b0}}};
    localparam signed [ACCW-1:0] AMAX = {1'b0, {(ACCW-1){1'b1}}};
    // post-adder constant p << 17 | 2^16: p + rshift_round(x, 17) = (x + p 2^17 + 2^16) >>> 17
    function signed [ACCW-1:0] pc;
        input signed [OPW-1:0] p;
        pc = {{(ACCW-OPW-FR){p[OPW-1]}}, p, 1'b1, {(FR-1){1'b0}}};
    endfunction
    // sat18 of p >>> 17 (|p| < 2^36): fits iff p[47:34] all equal
    function signed [OPW-1:0] sat_hi;
        input [ACCW-FR-1:0] p;             // p[47:17]
        sat_hi = ((&p[ACCW-FR-1:OPW-1]) | ~(|p[ACCW-FR-1:OPW-1])) ? p[OPW-1:0] :
                 (p[ACCW-FR-1] ? OMIN : OMAX);
    endfunction

    // column-valid pipeline: cvp[k] = column valid in cycle G1+k
    reg [7:1] cvp;
    reg       rnd6, rnd7, rnd8;

    // ---- mul1: p2 * wn + p1 2^17 + 2^16 ----
    wire signed [ACCW-1:0] prod1;
    mpc_mul18 u_mul1 (.clk(clk), .rst(rst), .a(wn), .b(p2), .c(pc(p1)), .c_clr(1'b0), .ab_clr(1'b0), .p(prod1));
    wire signed [OPW-1:0] h = sat_hi(prod1[ACCW-1:FR]);              // G1+2
    wire h_sat = ~((&prod1[ACCW-1:PW-2]) | ~(|prod1[ACCW-1:PW-2]));

    // ---- mul2: h * wn + p0 2^17 + 2^16  (or t * wn) ----
    mpc_mul18 u_mul2 (.clk(clk), .rst(rst), .a(m2_t ? t : h), .b(wn), .c(pc(p0)), .c_clr(m2_t), .ab_clr(1'b0),
                      .p(prod2));
    wire signed [OPW-1:0] k = sat_hi(prod2[ACCW-1:FR]);              // G1+4
    wire k_sat = ~((&prod2[ACCW-1:PW-2]) | ~(|prod2[ACCW-1:PW-2]));

    // ---- mul3: k * a  (or u18 * a [+ 2^17 - 1], or 0 * 0 + ((ur >>> 4) << 17)) ----
    reg  signed [OPW-1:0] u18;
    wire signed [ACCW-1:0] prod3;
    wire m3_c = m3_rnd & ~m3_ur & u18[OPW-1];
    // c of mul3, registered in fabric: the ur field is cleared through the flip-flops' reset;
    // it shares only the round bit with the constants.  Round step: prod3 = 0 * 0 + 2^(DSH-1).
    reg  [ACCW-1:0] c3u, c3k;
    always @(posedge clk) begin
        if (rst || !m3_ur) c3u <= {ACCW{1'b0}};
        else               c3u <= {{(ACCW-UW+VSH-FR){ur[UW-1]}}, ur[UW-1:VSH], {FR{1'b0}}};
        if (rst) c3k <= {ACCW{1'b0}};
        else     c3k <= {{(ACCW-DSH){1'b0}}, rnd, {(DSH-1-FR){1'b0}}, {FR{m3_c}}};
    end
    mpc_mul18 #(.CREG(0)) u_mul3 (
        .clk(clk), .rst(rst), .a(m3_u ? u18 : k), .b(a), .c(c3u | c3k), .c_clr(1'b0), .ab_clr(rnd | m3_ur),
        .p(prod3)
    );
    assign u_lim = prod3[FR+UW-VSH-1:FR];

    // ---- stage a (G1+6): prod3 << s[1:0]; term overflow (s >= 13) ----
    wire signed [PW-1:0] p3 = prod3[PW-1:0];
    wire [TAW-1:0] ta = {{3{p3[PW-1]}}, p3} << s[1:0];
    // (p3 << s) fits 48 bit iff p3[35 : 47-s] all equal (s <= 12: always)
    wire [2:0] p3x = p3[PW-2:PW-4] ^ {3{p3[PW-1]}};
    wire t_ovf = (s == 4'd13 && p3x[2]) || (s == 4'd14 && |p3x[2:1]) || (s == 4'd15 && |p3x[2:0]);
    // A saturated term is encoded without a multiplexer: ta_r = 2^35 - 1 (set), sh_r = 3 (set),
    // fill = 1 gives tb = AMAX; for AMIN = AMAX + 1 (mod 2^48) the adder gets a carry-in and a
    // negative extension bit.  (Reset state: ta_r[34:0] ones, sh_r = 3; don't-care values.)
    reg  [TAW-1:0] ta_r;
    reg  [1:0]     sh_r;
    reg            fill_r, tl_r;

    // ---- stage b + accumulate (G1+7): acc = sat48(acc + sat48(ta << 4 sh)) ----
    wire [ACCW+11:0] tbx = {{(ACCW-TAW){ta_r[TAW-1]}}, ta_r, {12{fill_r}}};
    reg  [ACCW-1:0]  tb;
    always @* begin
        case (sh_r)
            2'd0:    tb = tbx[12 +: ACCW];
            2'd1:    tb = tbx[8 +: ACCW];
            2'd2:    tb = tbx[4 +: ACCW];
            default: tb = tbx[0 +: ACCW];
        endcase
    end
    // The accumulator saturates without a multiplexer: on overflow acc = AMAX (bits 46:0 set,
    // bit 47 reset through the flip-flops' synchronous set / reset) and nsat = 1 marks AMIN,
    // which enters the next addition as AMAX + carry-in (like a saturated term).  fresh = 1
    // (after clr / acc_clr) makes the next accumulation start from 0.
    reg             nsat, fresh;
    wire [ACCW-1:0] acc_g = acc & {ACCW{~fresh}};
    wire            n_g   = nsat & ~fresh;
    // T + G + c written as {T, 0} - {~G, ~c}: keeps the term on the carry chain's DI inputs
    wire [ACCW+1:0] sumx  = {tb[ACCW-1] | tl_r, tb, 1'b0} - {~(acc_g[ACCW-1] | n_g), ~acc_g, ~(n_g | tl_r)};
    wire [ACCW:0]   sum   = sumx[ACCW+1:1];
    wire            a_neg2 = n_g & tl_r;                 // AMIN + AMIN: sure negative overflow
    wire            a_ovf = (sum[ACCW] ^ sum[ACCW-1]) | a_neg2;
    wire            a_ng  = sum[ACCW] | a_neg2;          // overflow direction: negative
    wire            acc_en = cvp[7] || rnd8 || acc_x;

    always @(posedge clk) begin
        if (rst) begin
            cvp <= 7'd0;
            rnd6 <= 1'b0;
            rnd7 <= 1'b0;
            rnd8 <= 1'b0;
            u18 <= {OPW{1'b0}};
            fill_r <= 1'b0;
            tl_r <= 1'b0;
            nsat <= 1'b0;
            fresh <= 1'b1;
            f_gain <= 1'b0;
            f_term <= 1'b0;
            f_acc <= 1'b0;
            f_du <= 1'b0;
        end else begin
            cvp <= {cvp[6:1], cv};
            rnd6 <= rnd;
            rnd7 <= rnd6;
            rnd8 <= rnd7;
            if (u_ld) u18 <= a_next;
            fill_r <= t_ovf;
            tl_r <= t_ovf & p3[PW-1];
            if (clr || acc_clr) begin
                fresh <= 1'b1;
                nsat <= 1'b0;
            end else if (acc_en) begin
                fresh <= 1'b0;
                nsat <= a_ovf & a_ng;
            end
            if (clr) begin
                f_gain <= 1'b0;
                f_term <= 1'b0;
                f_acc <= 1'b0;
                f_du <= 1'b0;
            end else begin
                if (cvp[2] && h_sat) f_gain <= 1'b1;
                if (cvp[4] && k_sat) f_gain <= 1'b1;
                if ((cvp[6] && t_ovf) || f_or[0]) f_term <= 1'b1;
                if ((cvp[7] && a_ovf) || f_or[1]) f_acc <= 1'b1;
                if ((rnd8 && a_ovf) || f_or[2]) f_du <= 1'b1;
            end
        end
    end

    // accumulator register (reset value AMAX; only read after an accumulation from fresh)
    always @(posedge clk) begin
        if (rst || (acc_en && a_ovf)) begin
            acc <= AMAX;
        end else if (acc_en) begin
            acc <= sum[ACCW-1:0];
        end
    end

    always @(posedge clk) begin
        if (rst || t_ovf) begin
            ta_r[PW-2:0] <= {(PW-1){1'b1}};
            ta_r[PW-1]   <= 1'b0;
            sh_r         <= 2'd3;
        end else begin
            ta_r[PW-1:0] <= ta[PW-1:0];
            sh_r         <= s[3:2];
        end
        if (rst) ta_r[TAW-1:PW] <= {(TAW-PW){1'b0}};
        else     ta_r[TAW-1:PW] <= ta[TAW-1:PW];
    end

    // rounding remainders and the upper product bits are dropped by design
    wire unused_ok = &{1'b0, sumx[0], prod1[FR-1:0], prod2[FR-1:0], prod3[ACCW-1:FR+UW-VSH], prod3[FR-1:0], ur[VSH-1:0]};
endmodule
`default_nettype wire
