// mpc_operand: the MPC core's operand stream (model steps 1-3 and the operand of step 4).
//
// Captures the update's inputs at `cap` and, for one item per clock, produces
//   a = sat18(rshift_round(sat40(A - B), c))
// where A / B are selected from the captured inputs by the item:
//   COL  column j: signal col_sig (desc[5:0]) of the model's layout SIG_*, c = desc[10:6]
//        W_rel[m,o] = wref[m][o] - (position and o == 2 ? y2 : 0),  E[m,o] = wref[m][o] - y[o],
//        Y[o] = y[o] (0 for the angle in the position task), EBAR[o], DX[n];
//        m > min(N_img, N) and signal indices 59..63 read 0.
//   WN   scheduling speed: A = omega, c = ws; then wn = clamp(a, -(2^17-1)..2^17-1,
//        wn_min..wn_max) (step 1).
//   EB o aggregated error (step 2, alg2 only): inc = sat40(wref[0][o] - y[o]),
//        ebar[o] = sat40(ebar[o] + clamp(inc, +-ebar_lim[o])).
// Pipeline (item token at O0, desc valid at O1 from the column memory):
//   O1 decode, O2 select A/B, O3 A - B sat40, O4 barrel shift (or EB clamp),
//   O5 round + sat18 -> op (valid in O6; or EB ebar write), O6 WN clamp -> wn (valid O7).
// Flags (sticky, cleared by cap): f_signal (a column read a saturated signal), f_operand,
//   f_wn (wn != unsaturated rshift_round(omega, ws)), f_ebar, f_ebar_inc.
// Vector layouts: dx[n*40 +: 40], wref[(3*m + o)*40 +: 40] (m = 0..N), ebar[o*40 +: 40].
// Parameters: N horizon inputs (wref has N+1 entries), N <= EMPC_N_MAX.
// Reset: all registers 0.
`default_nettype none
`include "empc_formats.vh"
module mpc_operand #(
    parameter integer N = `EMPC_N
) (
    input  wire                          clk,
    input  wire                          rst,
    input  wire                          cap,
    input  wire signed [`EMPC_OPW-1:0]   y0,
    input  wire signed [`EMPC_OPW-1:0]   y1,
    input  wire signed [`EMPC_SIG_W-1:0] y2,
    input  wire signed [`EMPC_W_W-1:0]   omega,
    input  wire [5*`EMPC_SIG_W-1:0]      dx,
    input  wire [(N+1)*3*`EMPC_SIG_W-1:0] wref,
    input  wire [3*`EMPC_SIG_W-1:0]      ebar_prev,
    // fields of the running coefficient bank (stable during an update)
    input  wire                          alg2,
    input  wire                          pos,
    input  wire [4:0]                    neff3,      // 3 * min(N_img, N)
    input  wire [`EMPC_SIG_SHIFT_BITS-1:0] ws,
    input  wire signed [`EMPC_OPW-1:0]   wn_min,
    input  wire signed [`EMPC_OPW-1:0]   wn_max,
    input  wire [3*32-1:0]               ebar_lim,
    // item token at O0
    input  wire [1:0]                    kind,       // 0 none, 1 COL, 2 WN, 3 EB
    input  wire [1:0]                    eo,         // EB output index
    input  wire [`EMPC_SIG_SHIFT_BITS+5:0] desc,     // {shift, sig} of the column, valid at O1
    output reg  signed [`EMPC_OPW-1:0]   op,
    output reg  signed [`EMPC_OPW-1:0]   wn,
    output wire [3*`EMPC_SIG_W-1:0]      ebar,
    output reg                           f_signal,
    output reg                           f_operand,
    output reg                           f_wn,
    output reg                           f_ebar,
    output reg                           f_ebar_inc
);
    localparam integer SW   = `EMPC_SIG_W;            // 40
    localparam integer OPW  = `EMPC_OPW;              // 18
    localparam integer CB   = `EMPC_SIG_SHIFT_BITS;   // 5
    localparam [1:0] K_COL = 2'd1, K_WN = 2'd2, K_EB = 2'd3;
    // source index layout of the A multiplexer
    localparam integer S_W0    = 3 * N;               // wref[0][o]
    localparam integer S_Y     = S_W0 + 3;
    localparam integer S_EBAR  = S_Y + 3;
    localparam integer S_DX    = S_EBAR + 3;
    localparam integer S_OMEGA = S_DX + 5;
    localparam integer S_ZERO  = S_OMEGA + 1;
    localparam integer NSRC    = S_ZERO + 1;
    localparam integer XB      = (NSRC <= 32) ? 5 : 6;   // N <= 8: NSRC <= 40
    localparam integer NX      = 1 << XB;
    localparam signed [OPW-1:0] OMAX = {1'b0, {(OPW-1){1'b1}}};
    localparam signed [OPW-1:0] OMIN = {1'b1, {(OPW-1){1'b0}}};
    localparam signed [SW-1:0]  SMAXV = {1'b0, {(SW-1){1'b1}}};
    localparam signed [SW-1:0]  SMINV = {1'b1, {(SW-1){1'b0}}};
    localparam [5:0] G_WREL = `EMPC_SIG_WREL, G_E = `EMPC_SIG_E, G_Y = `EMPC_SIG_Y,
                     G_EBAR = `EMPC_SIG_EBAR, G_DX = `EMPC_SIG_DX, G_END = `EMPC_SIG_DX + 5;

    // ---- captured inputs ----
    reg signed [OPW-1:0] y0_r, y1_r;
    reg signed [SW-1:0]  y2_r;
    reg signed [`EMPC_W_W-1:0] om_r;
    reg [5*SW-1:0]       dx_r;
    reg [(N+1)*3*SW-1:0] wref_r;
    reg [3*SW-1:0]       ebar_r;
    assign ebar = ebar_r;

    // ---- O1: decode ----
    reg [1:0]    kind1, kind2, kind3, kind4, kind5, kind6;
    reg [1:0]    eo1, eo2, eo3, eo4, eo5;
    reg [XB-1:0] src1, src2;
    reg [1:0]    bsel1, bsel2;          // B = 0, y0, y1, y2
    reg [CB-1:0] c1, c2, c3, c4;
    reg          rb5;                   // rounding bit (c != 0) in O5
    wire [5:0]   sig = desc[5:0];
    reg  [5:0]   l;
    always @* begin
        src1  = S_ZERO[XB-1:0];
        bsel1 = 2'd0;
        c1    = desc[CB+5:6];
        l     = 6'd0;
        case (kind1)
            K_WN: begin
                src1 = S_OMEGA[XB-1:0];
                c1   = ws;
            end
            K_EB: begin
                src1  = S_W0[XB-1:0] + {{(XB-2){1'b0}}, eo1};
                bsel1 = eo1 + 2'd1;
                c1    = {CB{1'b0}};
            end
            K_COL: begin
                if (sig < G_E) begin
                    l = sig - G_WREL;
                    if (l < {1'b0, neff3}) begin
                        src1 = l[XB-1:0];
                        if (pos && (l % 6'd3) == 6'd2) bsel1 = 2'd3;
                    end
                end else if (sig < G_Y) begin
                    l = sig - G_E;
                    if (l < {1'b0, neff3}) begin
                        src1  = l[XB-1:0];
                        bsel1 = (l % 6'd3) == 6'd0 ? 2'd1 : (l % 6'd3) == 6'd1 ? 2'd2 : 2'd3;
                    end
                end else if (sig < G_EBAR) begin
                    l = sig - G_Y;
                    if (!(pos && l == 6'd2)) src1 = S_Y[XB-1:0] + l[XB-1:0];
                end else if (sig < G_DX) begin
                    l = sig - G_EBAR;
                    src1 = S_EBAR[XB-1:0] + l[XB-1:0];
                end else if (sig < G_END) begin
                    l = sig - G_DX;
                    src1 = S_DX[XB-1:0] + l[XB-1:0];
                end
            end
            default: ;
        endcase
    end

    // ---- O2: select ----
    wire [NX*SW-1:0] srcv;
    genvar g;
    generate
        for (g = 0; g < NX; g = g + 1) begin : g_src
            if (g < 3 * N) begin : g_wref
                assign srcv[g*SW +: SW] = wref_r[(g+3)*SW +: SW];
            end else if (g < S_Y) begin : g_w0
                assign srcv[g*SW +: SW] = wref_r[(g-S_W0)*SW +: SW];
            end else if (g == S_Y) begin : g_y0
                assign srcv[g*SW +: SW] = {{(SW-OPW){y0_r[OPW-1]}}, y0_r};
            end else if (g == S_Y + 1) begin : g_y1
                assign srcv[g*SW +: SW] = {{(SW-OPW){y1_r[OPW-1]}}, y1_r};
            end else if (g == S_Y + 2) begin : g_y2
                assign srcv[g*SW +: SW] = y2_r;
            end else if (g < S_DX) begin : g_ebar
                assign srcv[g*SW +: SW] = ebar_r[(g-S_EBAR)*SW +: SW];
            end else if (g < S_OMEGA) begin : g_dx
                assign srcv[g*SW +: SW] = dx_r[(g-S_DX)*SW +: SW];
            end else if (g == S_OMEGA) begin : g_om
                assign srcv[g*SW +: SW] = {{(SW-`EMPC_W_W){om_r[`EMPC_W_W-1]}}, om_r};
            end else begin : g_zero
                assign srcv[g*SW +: SW] = {SW{1'b0}};
            end
        end
    endgenerate
    wire [SW-1:0] a_sel = srcv[src2*SW +: SW];
    wire [SW-1:0] b_sel = (bsel2 == 2'd1) ? {{(SW-OPW){y0_r[OPW-1]}}, y0_r} :
                          (bsel2 == 2'd2) ? {{(SW-OPW){y1_r[OPW-1]}}, y1_r} :
                          (bsel2 == 2'd3) ? y2_r : {SW{1'b0}};
    reg signed [SW-1:0] av, bv;

    // ---- O3: S = sat40(A - B) ----
    wire signed [SW:0] d0 = {av[SW-1], av} - {bv[SW-1], bv};
    wire d_ovf = d0[SW] ^ d0[SW-1];
    wire signed [SW-1:0] d_s = d_ovf ? (d0[SW] ? SMINV : SMAXV) : d0[SW-1:0];
    reg  signed [SW-1:0] sv;

    // ---- O4: t2 = (S << 1) >>> c  |  EB: inc = clamp(S, +-lim) ----
    wire signed [SW:0] t2 = $signed({sv, 1'b0}) >>> c4;
    reg  signed [SW:0] t2r;
    wire [31:0] lim4 = ebar_lim[eo4*32 +: 32];
    wire signed [SW:0] lim_p = {{(SW-31){1'b0}}, lim4};
    wire signed [SW:0] lim_n = -lim_p;
    wire signed [SW:0] sv_x = {sv[SW-1], sv};
    wire inc_hi = sv_x > lim_p;
    wire inc_lo = sv_x < lim_n;
    wire signed [SW:0] inc = inc_hi ? lim_p : inc_lo ? lim_n : sv_x;
    reg  signed [SW:0] incr;

    // ---- O5: a = sat18((t2 + rb) >>> 1)  |  EB: ebar[o] = sat40(ebar[o] + inc) ----
    wire signed [SW:0]   a1 = {t2r[SW], t2r[SW:1]} + {{SW{1'b0}}, t2r[0] & rb5};
    wire a_ov = ~((&a1[(SW+1)-1:OPW-1]) | ~(|a1[(SW+1)-1:OPW-1]));   // upper bits not all equal
    wire a_hi = a_ov & ~a1[(SW+1)-1];
    wire a_lo = a_ov & a1[(SW+1)-1];
    wire signed [OPW-1:0] a_s = a_hi ? OMAX : a_lo ? OMIN : a1[OPW-1:0];
    wire signed [SW-1:0] eb_old = ebar_r[eo5*SW +: SW];
    wire signed [SW+1:0] e0 = {{2{eb_old[SW-1]}}, eb_old} + {incr[SW], incr};
    wire e_ov = ~((&e0[(SW+2)-1:SW-1]) | ~(|e0[(SW+2)-1:SW-1]));   // upper bits not all equal
    wire e_hi = e_ov & ~e0[(SW+2)-1];
    wire e_lo = e_ov & e0[(SW+2)-1];
    wire signed [SW-1:0] e_s = e_hi ? SMAXV : e_lo ? SMINV : e0[SW-1:0];
    reg                  wsat6;          // WN item: a saturated to 18 bit

    // ---- O6: wn = clamp(op) ----
    // min(max(w1, wn_min), wn_max) with both comparisons in parallel
    wire signed [OPW-1:0] w1 = (op == OMIN) ? -OMAX : op;
    wire w_lo  = w1 < wn_min;
    wire w_hi  = w1 > wn_max;
    wire w_inv = wn_min > wn_max;
    wire signed [OPW-1:0] w3 = w_lo ? (w_inv ? wn_max : wn_min) : (w_hi ? wn_max : w1);

    integer o;
    always @(posedge clk) begin
        if (rst) begin
            y0_r <= {OPW{1'b0}};
            y1_r <= {OPW{1'b0}};
            y2_r <= {SW{1'b0}};
            om_r <= {`EMPC_W_W{1'b0}};
            dx_r <= {(5*SW){1'b0}};
            wref_r <= {((N+1)*3*SW){1'b0}};
            ebar_r <= {(3*SW){1'b0}};
            kind1 <= 2'd0; kind2 <= 2'd0; kind3 <= 2'd0; kind4 <= 2'd0; kind5 <= 2'd0; kind6 <= 2'd0;
            eo1 <= 2'd0; eo2 <= 2'd0; eo3 <= 2'd0; eo4 <= 2'd0; eo5 <= 2'd0;
            src2 <= {XB{1'b0}};
            bsel2 <= 2'd0;
            c2 <= {CB{1'b0}}; c3 <= {CB{1'b0}}; c4 <= {CB{1'b0}};
            rb5 <= 1'b0;
            av <= {SW{1'b0}};
            bv <= {SW{1'b0}};
            sv <= {SW{1'b0}};
            t2r <= {(SW+1){1'b0}};
            incr <= {(SW+1){1'b0}};
            op <= {OPW{1'b0}};
            wn <= {OPW{1'b0}};
            wsat6 <= 1'b0;
            f_signal <= 1'b0; f_operand <= 1'b0; f_wn <= 1'b0; f_ebar <= 1'b0; f_ebar_inc <= 1'b0;
        end else begin
            // token pipeline
            kind1 <= kind; kind2 <= kind1; kind3 <= kind2; kind4 <= kind3; kind5 <= kind4; kind6 <= kind5;
            eo1 <= eo; eo2 <= eo1; eo3 <= eo2; eo4 <= eo3; eo5 <= eo4;
            // O1 -> O2
            src2  <= src1;
            bsel2 <= bsel1;
            c2 <= c1; c3 <= c2; c4 <= c3;
            rb5 <= (c4 != {CB{1'b0}});
            // O2 -> O3
            av <= a_sel;
            bv <= b_sel;
            // O3 -> O4
            sv <= d_s;
            // O4 -> O5
            t2r  <= t2;
            incr <= inc;
            // O5 -> O6
            op <= a_s;
            wsat6 <= a_hi | a_lo;
            if (cap) begin
                y0_r   <= y0;
                y1_r   <= y1;
                y2_r   <= y2;
                om_r   <= omega;
                dx_r   <= dx;
                wref_r <= wref;
                ebar_r <= ebar_prev;
                f_signal <= 1'b0; f_operand <= 1'b0; f_wn <= 1'b0; f_ebar <= 1'b0; f_ebar_inc <= 1'b0;
            end else begin
                if (kind3 == K_COL && d_ovf) f_signal <= 1'b1;
                if (kind4 == K_EB && alg2 && (inc_hi || inc_lo)) f_ebar_inc <= 1'b1;
                if (kind5 == K_COL && (a_hi || a_lo)) f_operand <= 1'b1;
                if (kind5 == K_EB && alg2) begin
                    for (o = 0; o < 3; o = o + 1)
                        if (eo5 == o[1:0]) ebar_r[o*SW +: SW] <= e_s;
                    if (e_hi || e_lo) f_ebar <= 1'b1;
                end
                if (kind6 == K_WN) begin
                    wn <= w3;
                    if (wsat6 || (w3 != op)) f_wn <= 1'b1;
                end
            end
        end
    end

endmodule
`default_nettype wire
