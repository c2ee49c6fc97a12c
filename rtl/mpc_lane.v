// mpc_lane: one row (d or q) of the explicit MPC law: polynomial gain, MAC, du, u_raw.
//
// Per column (one per clock, bit-exact to gen/empc/rtlmodel/mpc_core.py, step 4):
//   h    = sat18(p1 + rshift_round(p2 * wn, 17))          mul1
//   k    = sat18(p0 + rshift_round(h * wn, 17))           mul2     (eq. 29)
//   term = sat48((k * a) << s);  acc = sat48(acc + term)  mul3 + fabric accumulator
// The per-gain shift s (0..15) sits between the product and the accumulation, so
// the DSP48A1's own post-adder/accumulator cannot be used: shift, saturation and the
// 48-bit saturating accumulator are fabric logic.  Step 5 (ld_du, ld_u):
//   du = sat24(rshift_round(acc, ACC_FRAC - U_FRAC)),  u_raw = sat24(u_prev + du).
// Voltage limiter support (step 6, controlled by mpc_core): u18 = sat18(rshift_round(
// u_raw, U_FRAC - V_FRAC)); mul3 computes u18^2 (m3_sq) and u18 * f (m3_scale);
// u_lim = trunc0(u18 * f / 2^17) << (U_FRAC - V_FRAC); mul1 takes external operands
// (m1_aux: m1_a * m1_b) so the limiter needs no multiplier of its own.
// Timing (cycle G1 = cycle in which cv and p2 are valid): p1 valid in G1+2, p0 and a
// in G1+4, s in G1+6; acc includes the column from G1+8.  Multiplier products appear
// 2 cycles after their operands (prod1, prod3 outputs).
// Ports: see the port list; f_* are sticky saturation flags (cleared by clr).
// Parameters: none (widths from empc_formats.vh).
// Reset / clr: acc, du, u_raw, u18 and flags clear to 0.
`default_nettype none
`include "empc_formats.vh"
module mpc_lane (
    input  wire                            clk,
    input  wire                            rst,
    input  wire                            clr,       // start of an update: acc = 0, flags = 0
    input  wire signed [`EMPC_OPW-1:0]     wn,        // scheduling speed Q1.17
    input  wire                            cv,        // column valid (cycle G1)
    input  wire signed [`EMPC_OPW-1:0]     p2,        // G1
    input  wire signed [`EMPC_OPW-1:0]     p1,        // G1+2
    input  wire signed [`EMPC_OPW-1:0]     p0,        // G1+4
    input  wire signed [`EMPC_OPW-1:0]     a,         // G1+4 operand
    input  wire [`EMPC_PROD_SHIFT_BITS-1:0] s,        // G1+6 product shift
    input  wire                            m1_aux,    // mul1 operands from m1_a / m1_b
    input  wire signed [`EMPC_OPW-1:0]     m1_a,
    input  wire signed [`EMPC_OPW-1:0]     m1_b,
    input  wire                            m3_sq,     // mul3 operands (u18, u18)
    input  wire                            m3_scale,  // mul3 operands (u18, f)
    input  wire signed [`EMPC_OPW-1:0]     f,
    input  wire                            ld_du,     // acc final: load du
    input  wire                            ld_u,      // load u_raw = u_prev + du
    input  wire signed [`EMPC_U_W-1:0]     u_prev,
    output wire signed [2*`EMPC_OPW-1:0]   prod1,     // mul1 product
    output wire signed [2*`EMPC_OPW-1:0]   prod3,     // mul3 product
    output reg  signed [`EMPC_U_W-1:0]     du,
    output reg  signed [`EMPC_U_W-1:0]     u_raw,
    output wire signed [`EMPC_U_W-1:0]     u_lim,     // limited u from prod3 (m3_scale + 2)
    output reg                             f_gain,
    output reg                             f_term,
    output reg                             f_acc,
    output reg                             f_du,
    output reg                             f_u
);
    localparam integer OPW  = `EMPC_OPW;                 // 18
    localparam integer PW   = 2 * OPW;                   // 36 product
    localparam integer ACCW = `EMPC_ACCW;                // 48
    localparam integer UW   = `EMPC_U_W;                 // 24
    localparam integer SB   = `EMPC_PROD_SHIFT_BITS;     // 4
    localparam integer SMAX = (1 << SB) - 1;             // 15
    localparam integer TW   = PW + SMAX;                 // 51: exact shifted product
    localparam integer DSH  = `EMPC_ACC_FRAC - `EMPC_U_FRAC;   // 24
    localparam integer VSH  = `EMPC_U_FRAC - `EMPC_V_FRAC;     // 4
    localparam integer FR   = OPW - 1;                   // 17: Q1.17 scaling
    localparam integer GW   = PW - FR + 2;               // 21: gain sum
    localparam signed [OPW-1:0]  OMAX = {1'b0, {(OPW-1){1'b1}}};
    localparam signed [OPW-1:0]  OMIN = {1'b1, {(OPW-1){1'b0}}};
    localparam signed [ACCW-1:0] AMAX = {1'b0, {(ACCW-1){1'b1}}};
    localparam signed [ACCW-1:0] AMIN = {1'b1, {(ACCW-1){1'b0}}};
    localparam signed [UW-1:0]   UMAXV = {1'b0, {(UW-1){1'b1}}};
    localparam signed [UW-1:0]   UMINV = {1'b1, {(UW-1){1'b0}}};

    // column-valid pipeline: cvp[k] = column valid in cycle G1+k
    reg [7:1] cvp;
    always @(posedge clk) begin
        if (rst) cvp <= 7'd0;
        else     cvp <= {cvp[6:1], cv};
    end


    // ---- mul1: p2 * wn (or limiter operands) ----
    mpc_mul18 u_mul1 (
        .clk(clk), .rst(rst),
        .a(m1_aux ? m1_a : wn),
        .b(m1_aux ? m1_b : p2),
        .p(prod1)
    );

    // h = sat18(p1 + rnd17(p2 * wn))   (cycle G1+2)
    // rshift_round(x, n) = (x >>> n) + x[n-1]: one adder with the rounding bit as carry-in
    wire signed [GW-1:0] h0 = {{(GW-OPW){p1[OPW-1]}}, p1} + {{(GW-PW+FR){prod1[PW-1]}}, prod1[PW-1:FR]}
                              + {{(GW-1){1'b0}}, prod1[FR-1]};
    wire h_ov = ~((&h0[GW-1:OPW-1]) | ~(|h0[GW-1:OPW-1]));   // upper bits not all equal
    wire h_hi = h_ov & ~h0[GW-1];
    wire h_lo = h_ov & h0[GW-1];
    wire signed [OPW-1:0] h = h_hi ? OMAX : h_lo ? OMIN : h0[OPW-1:0];

    // ---- mul2: h * wn ----
    wire signed [PW-1:0] prod2;
    mpc_mul18 u_mul2 (.clk(clk), .rst(rst), .a(h), .b(wn), .p(prod2));

    // k = sat18(p0 + rnd17(h * wn))   (cycle G1+4)
    wire signed [GW-1:0] k0 = {{(GW-OPW){p0[OPW-1]}}, p0} + {{(GW-PW+FR){prod2[PW-1]}}, prod2[PW-1:FR]}
                              + {{(GW-1){1'b0}}, prod2[FR-1]};
    wire k_ov = ~((&k0[GW-1:OPW-1]) | ~(|k0[GW-1:OPW-1]));   // upper bits not all equal
    wire k_hi = k_ov & ~k0[GW-1];
    wire k_lo = k_ov & k0[GW-1];
    wire signed [OPW-1:0] k = k_hi ? OMAX : k_lo ? OMIN : k0[OPW-1:0];

    // ---- limiter operand: u18 = sat18(rshift_round(u_raw, VSH)) ----
    wire signed [UW-VSH:0] ur = {u_raw[UW-1], u_raw[UW-1:VSH]} + {{(UW-VSH){1'b0}}, u_raw[VSH-1]};
    wire ur_ov = ~((&ur[(UW-VSH+1)-1:OPW-1]) | ~(|ur[(UW-VSH+1)-1:OPW-1]));   // upper bits not all equal
    wire ur_hi = ur_ov & ~ur[(UW-VSH+1)-1];
    wire ur_lo = ur_ov & ur[(UW-VSH+1)-1];
    wire signed [OPW-1:0] u18 = ur_hi ? OMAX : ur_lo ? OMIN : ur[OPW-1:0];
    reg  signed [OPW-1:0] u18_r;

    // ---- mul3: k * a (or u18^2, u18 * f) ----
    mpc_mul18 u_mul3 (
        .clk(clk), .rst(rst),
        .a(m3_scale ? u18_r : m3_sq ? u18 : k),
        .b(m3_scale ? f     : m3_sq ? u18 : a),
        .p(prod3)
    );

    // term = sat48(prod3 << s)   (cycle G1+6)
    wire signed [TW-1:0] tx = {{SMAX{prod3[PW-1]}}, prod3} <<< s;
    wire t_ovf = ~((&tx[TW-1:ACCW-1]) | ~(|tx[TW-1:ACCW-1]));
    wire signed [ACCW-1:0] term = t_ovf ? (tx[TW-1] ? AMIN : AMAX) : tx[ACCW-1:0];
    reg  signed [ACCW-1:0] term_r;

    // acc = sat48(acc + term)   (cycle G1+7)
    reg  signed [ACCW-1:0] acc;
    wire signed [ACCW:0] acc0 = {acc[ACCW-1], acc} + {term_r[ACCW-1], term_r};
    wire a_ovf = acc0[ACCW] ^ acc0[ACCW-1];
    wire signed [ACCW-1:0] acc_s = a_ovf ? (acc0[ACCW] ? AMIN : AMAX) : acc0[ACCW-1:0];

    // du = sat24(rshift_round(acc, DSH))
    wire signed [ACCW-DSH:0] d1 = {acc[ACCW-1], acc[ACCW-1:DSH]} + {{(ACCW-DSH){1'b0}}, acc[DSH-1]};
    wire d_ov = ~((&d1[(ACCW-DSH+1)-1:UW-1]) | ~(|d1[(ACCW-DSH+1)-1:UW-1]));   // upper bits not all equal
    wire d_hi = d_ov & ~d1[(ACCW-DSH+1)-1];
    wire d_lo = d_ov & d1[(ACCW-DSH+1)-1];
    wire signed [UW-1:0] du_s = d_hi ? UMAXV : d_lo ? UMINV : d1[UW-1:0];

    // u_raw = sat24(u_prev + du)
    wire signed [UW:0] u0 = {u_prev[UW-1], u_prev} + {du[UW-1], du};
    wire u_ovf = u0[UW] ^ u0[UW-1];
    wire signed [UW-1:0] u_s = u_ovf ? (u0[UW] ? UMINV : UMAXV) : u0[UW-1:0];

    // u_lim = trunc0(prod3 / 2^17) << VSH   (|u18 * f| < 2^34: 19-bit quotient)
    wire q_up = prod3[PW-1] && (|prod3[FR-1:0]);
    wire signed [PW-FR:0] q1 = {prod3[PW-1], prod3[PW-1:FR]} + {{(PW-FR){1'b0}}, q_up};
    assign u_lim = {q1[UW-VSH-1:0], {VSH{1'b0}}};

    always @(posedge clk) begin
        if (rst) begin
            term_r <= {ACCW{1'b0}};
            acc    <= {ACCW{1'b0}};
            du     <= {UW{1'b0}};
            u_raw  <= {UW{1'b0}};
            u18_r  <= {OPW{1'b0}};
            f_gain <= 1'b0;
            f_term <= 1'b0;
            f_acc  <= 1'b0;
            f_du   <= 1'b0;
            f_u    <= 1'b0;
        end else begin
            term_r <= term;
            if (m3_sq) u18_r <= u18;
            if (clr) begin
                acc    <= {ACCW{1'b0}};
                f_gain <= 1'b0;
                f_term <= 1'b0;
                f_acc  <= 1'b0;
                f_du   <= 1'b0;
                f_u    <= 1'b0;
            end else begin
                if (cvp[2] && (h_hi || h_lo)) f_gain <= 1'b1;
                if (cvp[4] && (k_hi || k_lo)) f_gain <= 1'b1;
                if (cvp[6] && t_ovf) f_term <= 1'b1;
                if (cvp[7]) begin
                    acc <= acc_s;
                    if (a_ovf) f_acc <= 1'b1;
                end
                if (ld_du) begin
                    du <= du_s;
                    if (d_hi || d_lo) f_du <= 1'b1;
                end
                if (ld_u) begin
                    u_raw <= u_s;
                    if (u_ovf) f_u <= 1'b1;
                end
            end
        end
    end

    // rounding remainders are dropped by design
    wire unused_ok = &{1'b0, prod1[FR-2:0], prod2[FR-2:0]};
endmodule
`default_nettype wire
