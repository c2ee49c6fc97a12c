// mpc_operand: the MPC core's input buffer and operand ALU (model steps 1-3, the operand of
// step 4, u_raw of step 5 and the limiter's operands).
//
// Input buffer: 64 words of SIG_W bit per axis (2^AXB x 64, block RAM), written through
// in_we / in_addr = {axis, word} / in_wdata (word map EMPC_IN_*: y[o] at IN_Y + o, omega,
// dx[n], u_prev[i], ebar_prev[o], wref[m][o] at IN_WREF + 3 m + o).  An update reads (does not
// copy) the words of its axis `raxis`: the writer keeps them stable from start to done; the
// other axes' words can be written meanwhile.  Scratch RAM: 16 x SIG_W-bit LUT RAM written by the ALU
// (y[o] copies at 0..2, the eq. 25 increments inc[o] at 4..6).
// ALU, one item per clock (kinds in mpc_items.vh), item token at O0:
//   O0  decode (columns: descriptor {c, sig} from the coefficient memory, read one cycle
//       ahead) -> registers
//   O1  read A = buffer word or 0, B = scratch word / header field / du[i] / 0 -> registers
//       (the ebar_lim clamp of EBAR columns / EBB items is applied here)
//   O2  D = A + B or A - B (SIG_W + 1 bit)
//   O3  S = satSW(D) (UR: sat24(D), also u_raw); scratch write (YC, EBA), EBA clamp
//       decision, EBB ebar; operand: Y1 = D << (1 + B) >>> 4 c[3:2], fit test above that window
//   O4  op = sat18(rshift_round(S, c - B)): Y1 >> c[1:0], round, saturate; op_next = f instead
//       when sel_f (limiter)
//   c is the stored (biased) shift field, B = SIG_SHIFT_BIAS: c = B is no shift, c < B a left
//   shift (column operands of large gains, model: rshift_round with a negative shift)
//   O5  op valid; WN / LO / HI: wn register (clamp steps), UMX: wn_s = wn, wn = op
// Items: YC o (copy y[o]), EBA o (inc = w_k[o] - y[o], clamp = |inc| > ebar_lim[o]),
//   WN (omega >> ws; c = the stored field ws + B), LO / HI (op = wn_min / wn_max; wn = max(wn, lo), then min(wn, hi)),
//   COL (W_rel, E, Y, EBAR, DX per the signal layout SIG_*; m > neff and indices 59..63 read
//   0; EBAR[o] = satSW(ebar_prev[o] + clamp(inc[o])) recomputed), UR i (u_prev[i] + du[i],
//   c = U_FRAC - V_FRAC: op = u18[i]), UMX / NUMX (op = +-u_max), EBB o (ebar[o]).
// Anti-windup of the speed integral (speed task, EBA 2): held (the EBA clamp patch with B = 0: increment 0)
//   when aw[0] (|i_q| at the hold current, mpc_axis) and inc[2] has the sign aw[1] (i_q < 0); f_ebar_inc
//   then too (model: mpc_core.update step 2).
// Flags (sticky, cleared by clr): f_signal (a column's signal saturated to SIG_W bit),
//   f_operand, f_wn (wn != unsaturated rshift_round(omega, ws)), f_ebar, f_ebar_inc (clamped or held), f_u.
// Parameters: NAXES (axes), AXW (axis index width, max(1, clog2(NAXES))); widths and the word map
//   from empc_formats.vh.
// Reset: registers 0 (the buffers are LUT RAM: not reset, initial contents 0), except two
//   copies each of c[3:2] (O3) and c[1:0] (O4) that reset to 3 or not at all: they only
//   select among zeros until an item arrives.
`default_nettype none
`include "empc_formats.vh"
`include "mpc_items.vh"
module mpc_operand #(
    parameter integer NAXES = 1,
    parameter integer AXW = 1
) (
    input  wire                          clk,
    input  wire                          rst,
    input  wire                          clr,        // start of an update: flags = 0
    // input buffer write port
    input  wire                          in_we,
    input  wire [5+$clog2(NAXES):0]      in_addr,    // {axis, word}
    input  wire [AXW-1:0]                raxis,      // axis of the update (stable from start to done)
    input  wire signed [`EMPC_SIG_W-1:0] in_wdata,
    // item token at O0
    input  wire [3:0]                    kind,
    input  wire [1:0]                    idx,        // o (YC, EBA, EBB) or row i (UR)
    input  wire [`EMPC_SIG_SHIFT_BITS+5:0] desc,     // {c, sig} of the column, valid at O0
    // fields of the running coefficient bank (stable during an update)
    input  wire                          alg2,
    input  wire                          pos,
    input  wire [1:0]                    aw,         // {i_q < 0, |i_q| at the hold current}: speed integral hold
    input  wire [3:0]                    neff,       // min(N_img, N, N_MAX)
    output reg  [2:0]                    hdr_field,  // header entry of the item at O0 (block RAM address)
    input  wire signed [`EMPC_SIG_W-1:0] hdr,       // that entry at O1, sign-extended (ebar_lim >= 0)
    // lanes / limiter
    input  wire signed [`EMPC_U_W-1:0]   du_d,       // at O1 of UR items
    input  wire signed [`EMPC_U_W-1:0]   du_q,
    input  wire                          sel_f,      // O4: op_next = f
    input  wire signed [`EMPC_OPW-1:0]   f,
    output wire signed [`EMPC_OPW-1:0]   op_next,
    output reg  signed [`EMPC_OPW-1:0]   op,
    output reg  signed [`EMPC_OPW-1:0]   wn,         // the lanes' scheduling speed
    output reg  signed [`EMPC_OPW-1:0]   wn_s,       // wn of this update (saved at UMX)
    output reg  signed [`EMPC_U_W-1:0]   ur_d,       // u_raw
    output reg  signed [`EMPC_U_W-1:0]   ur_q,
    output reg  [3*`EMPC_SIG_W-1:0]      ebar_s,     // ebar (EBB items)
    output reg                           f_signal,
    output reg                           f_operand,
    output reg                           f_wn,
    output reg                           f_ebar,
    output reg                           f_ebar_inc,
    output reg                           f_u
);
    localparam integer SW   = `EMPC_SIG_W;            // 32
    localparam integer OPW  = `EMPC_OPW;              // 18
    localparam integer UW   = `EMPC_U_W;              // 24
    localparam integer CB   = `EMPC_SIG_SHIFT_BITS;   // 4 (shift field 0..15)
    localparam integer B    = `EMPC_SIG_SHIFT_BIAS;   // 1: field c = shift + B (shift -1..14)
    localparam integer C_URI = `EMPC_U_FRAC - `EMPC_V_FRAC + B;
    localparam integer C_OKI = 14 + B;                // D overflow corners (O3, see y1e)
    localparam integer C_O15I = 15 + B;
    localparam [CB-1:0] C_UR  = C_URI[CB-1:0];
    localparam [CB-1:0] C_0   = B[CB-1:0];            // no shift (LO, HI, UMX, NUMX)
    localparam [4:0]    C_OK  = C_OKI[4:0];
    localparam [4:0]    C_O15 = C_O15I[4:0];
    generate if (CB != 4 || B < 0 || B > 2 || SW < OPW + 4 || SW > OPW + 22 - B ||
                 `EMPC_U_FRAC - `EMPC_V_FRAC > UW - OPW) begin : g_bad_params
        mpc_operand_unsupported_parameters u_error ();   // no such module: elaboration stops here
    end endgenerate
    localparam signed [OPW-1:0] OMAX = {1'b0, {(OPW-1){1'b1}}};
    localparam signed [OPW-1:0] OMIN = {1'b1, {(OPW-1){1'b0}}};
    localparam [5:0] IN_Y = `EMPC_IN_Y, IN_OMEGA = `EMPC_IN_OMEGA, IN_UPREV = `EMPC_IN_UPREV,
                     IN_EBAR = `EMPC_IN_EBAR, IN_WREF = `EMPC_IN_WREF, IN_DX = `EMPC_IN_DX;
    // header fields (mpc_coef_mem)
    localparam [2:0] F_WS = 3'd0, F_WNMIN = 3'd1, F_WNMAX = 3'd2, F_UMAX = 3'd3, F_LIM = 3'd4;
    // B operand sources
    localparam [1:0] B_SCR = 2'd0, B_HDR = 2'd1, B_DUD = 2'd2, B_DUQ = 2'd3;
    // scratch RAM slots
    localparam [3:0] R_Y = 4'd0, R_INC = 4'd4;
    generate if (F_LIM[1:0] != 2'd0 || R_Y[1:0] != 2'd0 || R_INC[1:0] != 2'd0) begin : g_bad_slots
        mpc_operand_unsupported_slots u_error ();         // o is ORed into these (no adder)
    end endgenerate
    // column decode table: sig -> {cat[2:0], m1[2:0], o[1:0], A word[5:0]}
    localparam [2:0] CT_ZERO = 3'd0, CT_WREL = 3'd1, CT_E = 3'd2, CT_Y = 3'd3, CT_EBAR = 3'd4, CT_DX = 3'd5;
    localparam integer TE = 14;
    function [64*TE-1:0] col_table;
        input [5:0] wref1;                // buffer word of wref[1][0]
        integer m1, o1, l;
        reg [TE-1:0] e;
        begin
            col_table = {(64*TE){1'b0}};                                   // CT_ZERO
            for (m1 = 0; m1 < `EMPC_N_MAX; m1 = m1 + 1)
                for (o1 = 0; o1 < 3; o1 = o1 + 1) begin
                    e = {CT_WREL, m1[2:0], o1[1:0], wref1 + m1[5:0] * 6'd3 + o1[5:0]};
                    col_table[(`EMPC_SIG_WREL + 3 * m1 + o1) * TE +: TE] = e;   // W_rel[m1 + 1][o1]
                    e[13:11] = CT_E;
                    col_table[(`EMPC_SIG_E + 3 * m1 + o1) * TE +: TE] = e;      // E[m1 + 1][o1]
                end
            for (l = 0; l < 3; l = l + 1) begin
                col_table[(`EMPC_SIG_Y + l) * TE +: TE] = {CT_Y, 3'd0, l[1:0], IN_Y + l[5:0]};
                col_table[(`EMPC_SIG_EBAR + l) * TE +: TE] = {CT_EBAR, 3'd0, l[1:0], IN_EBAR + l[5:0]};
            end
            for (l = 0; l < 5; l = l + 1)
                col_table[(`EMPC_SIG_DX + l) * TE +: TE] = {CT_DX, 5'd0, IN_DX + l[5:0]};
        end
    endfunction
    localparam [64*TE-1:0] COLTAB = col_table(IN_WREF + 6'd3);

    // ---- buffers ----
    localparam integer AXB = $clog2(NAXES);
    reg [SW-1:0] abuf [0:(`EMPC_IN_WORDS << AXB)-1];
    reg [SW-1:0] sbuf [0:15];
    integer bi;
    initial begin
        for (bi = 0; bi < (`EMPC_IN_WORDS << AXB); bi = bi + 1) abuf[bi] = {SW{1'b0}};
        for (bi = 0; bi < 16; bi = bi + 1) sbuf[bi] = {SW{1'b0}};
    end
    always @(posedge clk)
        if (in_we) abuf[in_addr] <= in_wdata;

    // ---- O0: decode (the descriptor of a column at O0 is valid at O0) -> O1 registers ----
    reg  [1:0]  idx1;
    reg  [2:0]  clamp_o, neg_o;         // EBA results per o
    reg         held2;                  // EBA 2 held (anti-windup): the clamp patch adds 0
    wire [TE-1:0] ent = COLTAB[desc[5:0]*TE +: TE];
    wire [2:0] e_cat = ent[13:11];
    wire [2:0] e_m1  = ent[10:8];
    wire [1:0] e_o   = ent[7:6];
    wire [5:0] e_aa  = ent[5:0];
    wire       e_inh = {1'b0, e_m1} < neff;
    // buffer word base + idx, as a table on idx (constants only, no adder)
    function [5:0] base_idx;
        input [5:0] base;
        input [1:0] i;
        begin
            case (i)
                2'd0:    base_idx = base;
                2'd1:    base_idx = base + 6'd1;
                2'd2:    base_idx = base + 6'd2;
                default: base_idx = base + 6'd3;
            endcase
        end
    endfunction
    reg  [5:0]  a_addr0;
    reg         a_zero0, b_zero0, sub0, nosig0, ebar0;
    reg  [1:0]  b_sel0;
    reg  [2:0]  hf0;
    always @* begin
        // sub does not matter when B = 0 (A + ~0 + 1 = A): 1 for all columns
        a_addr0 = 6'd0;
        a_zero0 = 1'b1;
        b_zero0 = 1'b1;
        b_sel0  = B_SCR;                    // y[o] (R_Y + o) / inc[o] (R_INC + o)
        sub0    = 1'b0;
        nosig0  = 1'b0;
        hf0     = F_LIM | {1'b0, idx};
        ebar0   = 1'b0;
        case (kind)
            `MPC_K_YC: begin
                a_addr0 = base_idx(IN_Y, idx);
                a_zero0 = 1'b0;
            end
            `MPC_K_EBA: begin
                a_addr0 = base_idx(IN_WREF, idx);
                a_zero0 = 1'b0;
                b_zero0 = 1'b0;
                sub0    = 1'b1;
            end
            `MPC_K_WN: begin
                a_addr0 = IN_OMEGA;
                a_zero0 = 1'b0;
                hf0     = F_WS;
            end
            `MPC_K_LO, `MPC_K_HI, `MPC_K_UMX, `MPC_K_NUMX: begin
                b_zero0 = 1'b0;
                b_sel0  = B_HDR;
                hf0     = (kind == `MPC_K_LO) ? F_WNMIN : (kind == `MPC_K_HI) ? F_WNMAX : F_UMAX;
                sub0    = (kind == `MPC_K_NUMX);
            end
            `MPC_K_UR: begin
                a_addr0 = base_idx(IN_UPREV, idx);
                a_zero0 = 1'b0;
                b_zero0 = 1'b0;
                b_sel0  = idx[0] ? B_DUQ : B_DUD;
                sub0    = 1'b0;
            end
            `MPC_K_EBB: begin
                a_addr0 = base_idx(IN_EBAR, idx);
                a_zero0 = 1'b0;
                ebar0   = 1'b1;
            end
            `MPC_K_COL: begin
                a_addr0 = e_aa;
                hf0     = F_LIM | {1'b0, e_o};
                sub0    = 1'b1;
                case (e_cat)
                    CT_WREL: begin
                        a_zero0 = !e_inh;
                        b_zero0 = !(e_inh && pos && e_o == 2'd2);
                    end
                    CT_E: begin
                        a_zero0 = !e_inh;
                        b_zero0 = !e_inh;
                    end
                    CT_Y:    a_zero0 = pos && e_o == 2'd2;
                    CT_EBAR: begin
                        a_zero0 = 1'b0;
                        ebar0   = 1'b1;
                        nosig0  = 1'b1;
                    end
                    CT_DX:   a_zero0 = 1'b0;
                    CT_ZERO: ;                  // signal indices 59..63
                    default: ;
                endcase
            end
            default: ;
        endcase
        // ebar_prev[o] + inc[o] (algorithm 2, no clamp; the clamp is patched in at O1)
        if (ebar0 && alg2) begin
            b_zero0 = 1'b0;
            sub0    = 1'b0;
        end
    end

    // ---- O1: clamp patch (EBA results of the same update may arrive at O1), read ----
    // o of the item = hdr_field[1:0] wherever it is used (F_LIM + o: EBB, EBAR, EBA, E), so the
    // scratch address R_Y + o / R_INC + o and the clamp patch take o from there
    reg  [5:0]  a_addr;
    reg         a_zero, b_zero, sub1r, nosig1, ebar1;
    reg  [1:0]  b_sel1;
    reg  [1:0]  hf1;                    // o of the item (low bits of its header field)
    reg  [CB-1:0] cd1;                  // desc c of the item (used for COL)
    wire [1:0]  eo1   = hf1;
    wire [3:0]  s_addr = (ebar1 ? R_INC : R_Y) | {2'd0, eo1};
    wire        cl1   = ebar1 && alg2 && clamp_o[eo1];
    wire [1:0]  b_sel = cl1 ? B_HDR : b_sel1;
    wire        sub1  = cl1 ? neg_o[eo1] : sub1r;
    wire        hz1   = cl1 && held2 && eo1 == 2'd2;      // held: B = 0 instead of the clamp
    reg  [CB-1:0] c1;
    always @* begin
        case (kind1)
            `MPC_K_WN:  c1 = hdr[CB-1:0];
            `MPC_K_COL: c1 = cd1;
            `MPC_K_UR:  c1 = C_UR;
            default:    c1 = C_0;
        endcase
    end
    always @* hdr_field = hf0;                      // registered read: hdr = that entry at O1
    wire [5+AXB:0] a_ra;
    generate if (AXB == 0) begin : g_ra1
        assign a_ra = a_addr;
    end else begin : g_ran
        assign a_ra = {raxis[AXB-1:0], a_addr};
    end endgenerate
    wire [SW-1:0] a_rd = abuf[a_ra];
    wire [SW-1:0] s_rd = sbuf[s_addr];
    reg  [SW-1:0] b_rd;
    always @* begin
        case (b_sel)
            B_SCR:   b_rd = s_rd;
            B_HDR:   b_rd = hdr;
            B_DUD:   b_rd = {{(SW-UW){du_d[UW-1]}}, du_d};
            default: b_rd = {{(SW-UW){du_q[UW-1]}}, du_q};
        endcase
    end
    reg signed [SW-1:0] av, bv;
    reg  [SW-2:0] lim2, lim3;           // ebar_lim[o] of an EBA item (O2, O3), < 2^(SW-1)

    // ---- O2: D = A +- B ----
    reg  [3:0]   kind1, kind2, kind3, kind4, kind5;
    reg  [1:0]   idx2, idx3;
    reg          sub2, nosig2, nosig3;
    reg  [CB-1:0] c2, c3;
    // O3 item decode, registered at O2 (one flip-flop per use instead of kind3 / idx3 logic)
    reg          yc3, eba3, ur3;
    reg  [2:0]   eba3_o;                // EBA item for o
    // A + (B ^ sub) + sub, the carry-in as an extra LSB (keeps A on the carry chain's DI inputs)
    wire [SW+1:0] d0x = {av[SW-1], av, 1'b1} + {({bv[SW-1], bv} ^ {(SW+1){sub2}}), sub2};
    wire [SW:0]  d0 = d0x[SW+1:1];
    reg  [SW:0]  dv;

    // ---- O3: S = satSW(D) (sat24(D) for UR items), Y1 = {S, 0}, first shift stage ----
    wire         d_sgn = dv[SW];
    wire         d_ovf = dv[SW] ^ dv[SW-1];
    wire         u_fit = (&dv[SW:UW-1]) | ~(|dv[SW:UW-1]);
    // One saturation serves the scratch / ebar writes (satSW) and u_raw (sat24, sign-extended):
    // for UR items the operand u18 = sat18(rshift_round(S, C_UR)) is the same from either,
    // because |sat24(D)| >= 2^(UW-1) saturates 18 bit as well for C_UR <= UW - OPW.
    wire         s_fit = ur3 ? u_fit : ~d_ovf;
    wire [SW-1:0] s_sat = ur3 ? {{(SW-UW+1){d_sgn}}, {(UW-1){~d_sgn}}} : {d_sgn, {(SW-1){~d_sgn}}};
    wire [SW-1:0] sv   = s_fit ? dv[SW-1:0] : s_sat;
    wire [SW-1:0] s_y1 = sv;             // S (items with c = 0: scratch / ebar writes)
    wire [UW-1:0] u_s  = sv[UW-1:0];    // UR: u_raw = sat24(D)
    // EBA: clamp = |inc| > lim: the sign of D - lim - 1 (D >= 0) or D + lim (D < 0), i.e.
    // D - (lim ^ sgn) - 1 on SW + 2 bits (one carry chain: the -1 enters as an extra LSB)
    wire [SW+1:0] lx    = {d_sgn, {2'b00, lim3} ^ {(SW+1){d_sgn}}};
    wire [SW+2:0] ccmpx = {dv[SW], dv, 1'b0} - {lx, 1'b1};
    wire          clamp = ccmpx[SW+2] ^ ~d_sgn;
    // anti-windup (EBA 2: held when inc[2] has the sign of i_q)
    wire          held3  = alg2 && !pos && aw[0] && (d_sgn == aw[1]);    // EBA 2: D = inc[2]
    // op = sat18(rshift_round(S << B, c)) = sat18(rshift_round(S, c - B)), c = 4 c[3:2] + c[1:0]
    // (the stored field): Y1 >>> 4 c[3:2] here (a 4:1 multiplexer per bit), >> c[1:0], rounding
    // and saturation at O4.  The shift takes the unsaturated D (SW + 1 bit; Y1 = D << (1 + B)),
    // which keeps the multiplexers off the saturation logic: when D overflows SW bit, S and D
    // give the same result for c <= 13 + B and for c = 14 + B, D > 0 (saturated); for c = 14 + B,
    // D < 0 (OMIN) and c = 15 + B (+-2^16; none for B >= 1), both not saturated, O4 overrides it
    // (o_k, o_15).  For UR items (S = sat24(D), c = C_UR) D gives the same operand too: both
    // saturate when D does not fit 24 bit.
    wire [SW+13:0] y1e = {{(12-B){d_sgn}}, dv, {(B+1){1'b0}}};
    // c[3:2] in three copies, one per output bit group (i / 4) mod 3, for the same reason as
    // c[1:0] at O4 (bits 4 and 8 apart would share 2:1 halves): c3[3:2] and two more that
    // differ in their reset only (dv = 0 after reset, so y2 = 0 whatever they hold)
    reg  [1:0]   c3b, c3c;
    always @(posedge clk) begin
        if (rst) c3b <= 2'b11;
        else     c3b <= c2[3:2];
        c3c <= c2[3:2];
    end
    reg  [OPW+3:0] y2;                  // Y1 >>> 4 c[3:2], positions 0..21
    reg  [1:0]   c3i;
    integer      bi2;
    always @* begin
        for (bi2 = 0; bi2 <= OPW + 3; bi2 = bi2 + 1) begin
            case ((bi2 / 4) % 3)
                0:       c3i = c3[3:2];
                1:       c3i = c3b;
                default: c3i = c3c;
            endcase
            case (c3i)
                2'd0:    y2[bi2] = y1e[bi2];
                2'd1:    y2[bi2] = y1e[bi2 + 4];
                2'd2:    y2[bi2] = y1e[bi2 + 8];
                default: y2[bi2] = y1e[bi2 + 12];
            endcase
        end
    end
    // the result fits 18 bit iff Y1 bits [SW-1+B : 18 + c] equal the sign (Y1 bit p = S bit
    // p-1-B): bits above the y2 window (>= 22 + 4 c[3:2]) by groups of 4, the rest in y2
    // (>= 18 + c[1:0]) at O4; y_x holds positions 18..39, zero (= equal to the sign) above SW-1+B.  It is taken
    // from D (S bit = D bit unless D overflows SW bit: then all differ from the sign), which
    // keeps it off the saturation logic.  For UR items (S = sat24(D), c = C_UR) this can only
    // differ when D does not fit 24 bit; the operand then saturates anyway (nf_lo sees it).
    wire [21:0]  y_x   = {{(22-SW+OPW-B){1'b0}}, (dv[SW-2:OPW-1-B] ^ {(SW-OPW+B){d_sgn}}) | {(SW-OPW+B){d_ovf}}};
    wire         g22   = |y_x[7:4];
    wire         g26   = |y_x[11:8];
    wire         g30   = |y_x[15:12];
    wire         g34   = |y_x[21:16];
    wire         nf_hi = g34 | (c3[3:2] < 2'd3 && g30) | (c3[3:2] < 2'd2 && g26) | (c3[3:2] == 2'd0 && g22);
    reg  [OPW+3:0] y2r;
    reg          nf_hr, y_sgn, o_k, o_15;

    // ---- O4: >> c[1:0] (a 4:1 multiplexer per bit, also the rounding incrementer's input) ----
    // c[1:0] is registered three times, one copy per output bit i mod 3: with a select of its
    // own per class no two bits within a distance of 2 share a 2:1 half of their multiplexers,
    // so that each bit maps to one LUT6 (instead of a shared LUT3 + a LUT5).  The copies differ
    // in their reset (0, 1, none) only, so that synthesis keeps them apart; y2r = 0 after reset,
    // hence y3 = 0 whatever the copies hold.
    reg  [1:0]   c4a, c4b, c4c;
    always @(posedge clk) begin
        if (rst) c4b <= 2'b11;
        else     c4b <= c3[1:0];
        c4c <= c3[1:0];
    end
    reg  [OPW:0] y3;                    // S >>> (c - 1): y3[0] is the rounding bit
    reg  [1:0]   c4i;
    integer      bi3;
    always @* begin
        for (bi3 = 0; bi3 <= OPW; bi3 = bi3 + 1) begin
            case (bi3 % 3)
                0:       c4i = c4a;
                1:       c4i = c4b;
                default: c4i = c4c;
            endcase
            case (c4i)
                2'd0:    y3[bi3] = y2r[bi3];
                2'd1:    y3[bi3] = y2r[bi3 + 1];
                2'd2:    y3[bi3] = y2r[bi3 + 2];
                default: y3[bi3] = y2r[bi3 + 3];
            endcase
        end
    end
    // a1 = y3 >> 1 + y3[0] (the carry-in as an extra LSB); it can only overflow upwards
    wire [OPW:0] a1x   = {y3[OPW:1], y3[0]} + {{OPW{1'b0}}, y3[0]};
    wire [OPW-1:0] a1  = a1x[OPW:1];
    wire [3:0]   y2x   = y2r[OPW+3:OPW] ^ {4{y_sgn}};     // y2 positions 18..21
    wire         nf_lo = y2x[3] | (c4a < 2'd3 && y2x[2]) | (c4a < 2'd2 && y2x[1]) | (c4a == 2'd0 && y2x[0]);
    wire         a_sat = ~o_k & (nf_hr | nf_lo | (a1[OPW-1] & ~y3[OPW]));
    wire signed [OPW-1:0] a_s = o_k ? {y_sgn, o_15, {(OPW-2){1'b0}}} : a_sat ? (y_sgn ? OMIN : OMAX) : a1;
    assign op_next = sel_f ? f : a_s;
    reg          sat5;

    // ---- O5: wn clamp steps: L = wn < op + k (k = 1 for HI) ----
    wire         is_hi = (kind5 == `MPC_K_HI);
    wire [OPW+1:0] wdx = {wn[OPW-1], wn, 1'b1} + {~{op[OPW-1], op}, ~is_hi};
    wire [OPW:0] wd    = wdx[OPW+1:1];
    wire         w_lt  = wd[OPW];

    integer o;
    always @(posedge clk) begin
        // scratch RAM write (O3)
        if (yc3 || eba3)
            sbuf[(eba3 ? R_INC : R_Y) | {2'd0, idx3}] <= s_y1;
        if (rst) begin
            kind1 <= `MPC_K_NONE; kind2 <= `MPC_K_NONE; kind3 <= `MPC_K_NONE;
            kind4 <= `MPC_K_NONE; kind5 <= `MPC_K_NONE;
            idx1 <= 2'd0; idx2 <= 2'd0; idx3 <= 2'd0;
            a_addr <= 6'd0; a_zero <= 1'b1; b_zero <= 1'b1; sub1r <= 1'b0; nosig1 <= 1'b0; ebar1 <= 1'b0;
            b_sel1 <= B_SCR; hf1 <= F_WS[1:0]; cd1 <= {CB{1'b0}};
            sub2 <= 1'b0; nosig2 <= 1'b0; nosig3 <= 1'b0;
            c2 <= {CB{1'b0}}; c3 <= {CB{1'b0}}; c4a <= 2'd0; yc3 <= 1'b0; eba3 <= 1'b0; ur3 <= 1'b0; eba3_o <= 3'd0;
            av <= {SW{1'b0}};
            bv <= {SW{1'b0}};
            lim2 <= {(SW-1){1'b0}}; lim3 <= {(SW-1){1'b0}};
            dv <= {(SW+1){1'b0}};
            y2r <= {(OPW+4){1'b0}}; nf_hr <= 1'b0; y_sgn <= 1'b0; o_k <= 1'b0; o_15 <= 1'b0;
            op <= {OPW{1'b0}};
            sat5 <= 1'b0;
            wn <= {OPW{1'b0}};
            wn_s <= {OPW{1'b0}};
            ur_d <= {UW{1'b0}};
            ur_q <= {UW{1'b0}};
            ebar_s <= {(3*SW){1'b0}};
            clamp_o <= 3'd0;
            neg_o <= 3'd0;
            held2 <= 1'b0;
            f_signal <= 1'b0; f_operand <= 1'b0; f_wn <= 1'b0; f_ebar <= 1'b0; f_ebar_inc <= 1'b0;
            f_u <= 1'b0;
        end else begin
            // token pipeline
            kind1 <= kind; kind2 <= kind1; kind3 <= kind2; kind4 <= kind3; kind5 <= kind4;
            idx1 <= idx; idx2 <= idx1; idx3 <= idx2;
            // O0 -> O1
            a_addr <= a_addr0;
            a_zero <= a_zero0;
            b_zero <= b_zero0;
            sub1r  <= sub0;
            nosig1 <= nosig0;
            ebar1  <= ebar0;
            b_sel1 <= b_sel0;
            hf1    <= hf0[1:0];
            cd1    <= desc[CB+5:6];
            // O1 -> O2
            av <= a_zero ? {SW{1'b0}} : a_rd;
            bv <= (b_zero || hz1) ? {SW{1'b0}} : b_rd;
            sub2 <= sub1;
            nosig2 <= nosig1;
            c2 <= c1;
            lim2 <= hdr[SW-2:0];
            // O2 -> O3
            dv <= d0;
            yc3 <= (kind2 == `MPC_K_YC);
            eba3 <= (kind2 == `MPC_K_EBA);
            ur3 <= (kind2 == `MPC_K_UR);
            for (o = 0; o < 3; o = o + 1)
                eba3_o[o] <= (kind2 == `MPC_K_EBA && idx2 == o[1:0]);
            c3 <= c2;
            nosig3 <= nosig2;
            lim3 <= lim2;
            // O3 -> O4
            y2r <= y2;
            nf_hr <= nf_hi;
            o_k <= d_ovf && ({1'b0, c3} == C_O15 || ({1'b0, c3} == C_OK && d_sgn));
            o_15 <= d_ovf && {1'b0, c3} == C_O15;
            y_sgn <= d_sgn;
            c4a <= c3[1:0];
            for (o = 0; o < 3; o = o + 1)
                if (eba3_o[o]) begin
                    clamp_o[o] <= clamp || (o == 2 && held3);
                    neg_o[o] <= d_sgn;
                end
            if (eba3_o[2]) held2 <= held3;
            if (kind3 == `MPC_K_EBB)
                for (o = 0; o < 3; o = o + 1)
                    if (idx3 == o[1:0]) ebar_s[o*SW +: SW] <= s_y1;
            if (ur3) begin
                if (idx3[0]) ur_q <= u_s;
                else         ur_d <= u_s;
            end
            // O4 -> O5
            op <= op_next;
            sat5 <= a_sat;
            // O5: wn
            case (kind5)
                `MPC_K_WN: wn <= op;
                `MPC_K_LO: if (w_lt) wn <= op;
                `MPC_K_HI: if (!w_lt) wn <= op;
                `MPC_K_UMX: begin
                    wn_s <= wn;
                    wn <= op;
                end
                default: ;
            endcase
            // flags
            if (clr) begin
                f_signal <= 1'b0; f_operand <= 1'b0; f_wn <= 1'b0; f_ebar <= 1'b0; f_ebar_inc <= 1'b0;
                f_u <= 1'b0;
            end else begin
                if (kind3 == `MPC_K_COL && d_ovf && !nosig3) f_signal <= 1'b1;
                if (eba3 && alg2 && (clamp || (eba3_o[2] && held3))) f_ebar_inc <= 1'b1;
                if (kind3 == `MPC_K_EBB && alg2 && d_ovf) f_ebar <= 1'b1;
                if (ur3 && !u_fit) f_u <= 1'b1;
                if (kind4 == `MPC_K_COL && a_sat) f_operand <= 1'b1;
                if ((kind5 == `MPC_K_WN && sat5) || (kind5 == `MPC_K_LO && w_lt) || (kind5 == `MPC_K_HI && !w_lt))
                    f_wn <= 1'b1;
            end
        end
    end

    wire unused_ok = &{1'b0, y1e[SW+13:OPW+16], a1x[0], ccmpx[SW+1:0], d0x[0], wdx[0], wd[OPW-1:0], hdr[SW-1], y_x[3:0], raxis};
endmodule
`default_nettype wire
