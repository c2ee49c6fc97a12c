// mpc_coef_mem: the MPC core's coefficient banks, two per axis (image layout of gen/empc/image.py).
//
// Banks are addressed k = {axis, bank} (NAXES axes: 2^AXB bank pairs, AXB = clog2(NAXES)).
// Write port: one 32-bit image word per clock (we, waxis, wbank, waddr = word address of the
// image layout, wdata).  Decoded as it is written:
//   A_CFG        algorithm[14:13], task[12] (1 = position), N[11:8], ncols[6:0] -> registers
//   A_WS .. A_EBAR+2  header RAM, one SIG_W-bit entry per field (sign-extended value):
//                field 0 ws = wdata[SIG_SHIFT_BITS-1:0];  1 / 2 wn_min / wn_max: signed 32 ->
//                clamped to +-(2^17-1);  3 u_max: unsigned 32 -> min(u_max, 2^17-1);
//                4..6 ebar_lim[o]: unsigned 32 -> min(ebar_lim, 2^(SIG_W-1)-1).
//                Field f is image word A_WS + f.
//   A_COLS + j   column j {shift[SIG_SHIFT_BITS+7:8], sig[5:0]}   -> descriptor memory
//   A_GAINS + 4 (64 i + j) + k   row i, column j: k = 0..2 p0, p1, p2 (signed 32, saturated
//                to 18 bit), k = 3 product shift [3:0]  -> coefficient / shift memories
//   other addresses (magic, used, checksum, unused) are ignored.
// ncols is clamped to MAX_COLS; neff = min(N_img, N, N_MAX) (horizon steps the core reads).
// Read side (bank {raxis, rbank}): synchronous reads, data valid one clock after the address:
// desc at ra_desc, p2 / p1 at ra_c, p0 at ra_p0, the product shifts at ra_s (s_clr reads 0 instead);
// the header entry hdr_field is read synchronously too (hdr, block RAM); the CFG fields are
// combinational outputs of the bank registers; pos_v[a] = the task of axis a's bank bank_v[a].
// Storage: block RAM (p0/p1/p2 x rows: 2 NA x 64 x 18 each; descriptors 2 NA x 64 x 10; shifts
// 2 NA x 64 x {4, 4}; NA = 2^AXB: one RAMB8 each up to four axes); header: block RAM 2 NA x 8 x
// SIG_W (one RAMB8 up to 16 axes); CFG fields: registers.
// Parameters: N (horizon inputs of the core, <= EMPC_N_MAX), NAXES, AXW (axis index width,
// max(1, AXB)).
// Reset: CFG registers of both banks clear to 0 (ncols = 0: an empty bank gives du = 0);
// memories are not reset (header initial contents 0); read registers clear to 0 (hdr: not reset).
`default_nettype none
`include "empc_formats.vh"
module mpc_coef_mem #(
    parameter integer N = `EMPC_N,
    parameter integer NAXES = 1,
    parameter integer AXW = 1,
    parameter integer DW = `EMPC_SIG_SHIFT_BITS + 6     // descriptor {c, sig}
) (
    input  wire                        clk,
    input  wire                        rst,
    input  wire                        we,
    input  wire [AXW-1:0]              waxis,
    input  wire                        wbank,
    input  wire [9:0]                  waddr,
    input  wire [31:0]                 wdata,
    input  wire [AXW-1:0]              raxis,
    input  wire                        rbank,
    input  wire [NAXES-1:0]            bank_v,     // active bank of every axis (pos_v)
    output wire [NAXES-1:0]            pos_v,
    input  wire [5:0]                  ra_desc,
    input  wire [5:0]                  ra_c,
    input  wire [5:0]                  ra_p0,
    input  wire [5:0]                  ra_s,
    input  wire                        s_clr,
    output reg  [DW-1:0]               desc,
    output reg  signed [`EMPC_OPW-1:0] p2_d,
    output reg  signed [`EMPC_OPW-1:0] p2_q,
    output reg  signed [`EMPC_OPW-1:0] p1_d,
    output reg  signed [`EMPC_OPW-1:0] p1_q,
    output reg  signed [`EMPC_OPW-1:0] p0_d,
    output reg  signed [`EMPC_OPW-1:0] p0_q,
    output wire [3:0]                  s_d,
    output wire [3:0]                  s_q,
    output wire                        alg2,
    output wire                        pos,
    output wire [6:0]                  ncols,
    output wire [3:0]                  neff,
    input  wire [2:0]                  hdr_field,
    output wire signed [`EMPC_SIG_W-1:0] hdr
);
    localparam integer OPW   = `EMPC_OPW;
    localparam integer SW    = `EMPC_SIG_W;
    localparam integer CB    = `EMPC_SIG_SHIFT_BITS;
    localparam integer MAXC  = `EMPC_MAX_COLS;     // 64
    localparam integer NEFF  = (N < `EMPC_N_MAX) ? N : `EMPC_N_MAX;
    localparam [9:0] A_CFG   = `EMPC_IMG_A_CFG;
    localparam [9:0] A_WS    = `EMPC_IMG_A_WS;
    localparam [9:0] A_HEND  = `EMPC_IMG_A_EBAR + 3;           // header fields A_WS .. A_EBAR+2
    localparam [9:0] A_COLS  = `EMPC_IMG_A_COLS;
    localparam [9:0] A_GAINS = `EMPC_IMG_A_GAINS;
    localparam [9:0] A_GEND  = `EMPC_IMG_A_GAINS + 8 * `EMPC_MAX_COLS;
    localparam [9:0] A_CEND  = `EMPC_IMG_A_COLS + `EMPC_MAX_COLS;
    localparam [2:0] F_WS = 3'd0, F_WNMIN = 3'd1, F_WNMAX = 3'd2, F_UMAX = 3'd3;
    localparam integer AXB = $clog2(NAXES);         // axis bits of a bank index
    localparam integer KW  = AXB + 1;               // bank index k = {axis, bank}
    localparam integer NK  = 1 << KW;
    // bank indices of the write and the read side
    wire [KW-1:0] wk, rk;
    generate if (AXB == 0) begin : g_k1
        assign wk = wbank;
        assign rk = rbank;
    end else begin : g_kn
        assign wk = {waxis[AXB-1:0], wbank};
        assign rk = {raxis[AXB-1:0], rbank};
    end endgenerate

    // ---- write decode ----
    wire [9:0] coff = waddr - A_COLS;
    wire [9:0] goff = waddr - A_GAINS;
    wire [9:0] hoff = waddr - A_WS;
    wire w_col  = we && waddr >= A_COLS  && waddr < A_CEND;
    wire w_gain = we && waddr >= A_GAINS && waddr < A_GEND;
    wire w_hdr_a = waddr >= A_WS && waddr < A_HEND;
    wire w_hdr  = we && w_hdr_a;
    wire [KW+5:0] wa_col  = {wk, coff[5:0]};
    wire [KW+5:0] wa_gain = {wk, goff[7:2]};
    wire g_row = goff[8];
    wire [1:0] g_k = goff[1:0];
    wire [2:0] h_f = hoff[2:0];

    // One clamped word dd serves the gain memories (sat18) and the header (per field), so the
    // per-bit logic is a single 3-input function dd[i] = keep ? wdata[i] : fill.
    //   gains, wn_min / wn_max: signed 32 -> sat18, sign-extended (the wn fields then map
    //                           -2^17 to -(2^17-1): bit 0 set when the saturated value is OMIN)
    //   u_max: unsigned 32 -> min(., 2^17-1);  ebar_lim: unsigned 32 -> min(., 2^(SW-1)-1)
    //   ws: wdata[CB-1:0] zero-extended
    // The data comes straight from a block RAM output (slow clock-to-out): the wide tests are
    // kept as explicit two-level trees (keep), so that the mapper cannot chain them.
    (* keep *) wire [2:0] hg_one = {&wdata[31:27], &wdata[26:22], &wdata[21:OPW-1]};
    (* keep *) wire [2:0] hg_any = {|wdata[31:27], |wdata[26:22], |wdata[21:OPW-1]};
    (* keep *) wire [2:0] lg_any = {|wdata[OPW-2:12], |wdata[11:6], |wdata[5:0]};
    (* keep *) wire hi_any = |hg_any;
    (* keep *) wire s_ok   = (&hg_one) | ~hi_any;                 // fits 18 bit signed
    wire w31    = wdata[31];
    wire m_ws   = w_hdr_a && h_f == F_WS;
    wire m_um   = w_hdr_a && h_f == F_UMAX;
    wire m_el   = w_hdr_a && h_f > F_UMAX;
    wire m_sg   = !(m_ws | m_um | m_el);                 // gains (any non-header word), wn limits
    wire m_wn   = w_hdr_a && (h_f == F_WNMIN || h_f == F_WNMAX);
    (* keep *) wire keep_l = (m_sg & s_ok) | (m_um & ~hi_any) | (m_el & ~w31) | m_ws;   // bits 0 .. CB-1
    (* keep *) wire keep_m = (m_sg & s_ok) | (m_um & ~hi_any) | (m_el & ~w31);          // bits CB .. OPW-2
    (* keep *) wire fill_l = m_sg ? ~w31 : (m_um | m_el);
    (* keep *) wire keep_h = m_el & ~w31;                                               // bits OPW-1 .. SW-2
    (* keep *) wire fill_h = w31 & ~(m_ws | m_um);
    wire fill_s = w31 & m_sg;                                                // bit SW-1
    // wn limit -2^17 -> -(2^17-1): saturated value OMIN <=> w31 and (in range, low bits 0, or below)
    (* keep *) wire wn_min1 = m_wn & w31 & (~s_ok | ~(|lg_any));
    reg  [SW-1:0] dd;
    integer di;
    always @* begin
        for (di = 0; di < SW; di = di + 1) begin
            if (di < CB)            dd[di] = keep_l ? wdata[di] : fill_l;
            else if (di < OPW - 1)  dd[di] = keep_m ? wdata[di] : fill_l;
            else if (di < SW - 1)   dd[di] = keep_h ? wdata[di] : fill_h;
            else                    dd[di] = fill_s;
        end
        dd[0] = dd[0] | wn_min1;
    end
    wire signed [OPW-1:0] wsat = dd[OPW-1:0];
    // CFG fields
    wire [3:0] w_n   = wdata[11:8];
    wire [3:0] w_ne  = (w_n > NEFF[3:0]) ? NEFF[3:0] : w_n;

    // ---- per-bank CFG registers ----
    // ncols = min(wdata[6:0], MAXC = 64): wdata[6] set clears bits 5:0 through the reset
    generate if (MAXC != 64) begin : g_bad_maxc
        mpc_coef_mem_unsupported_parameters u_error ();  // no such module: elaboration stops here
    end endgenerate
    reg        alg2_b [0:NK-1];
    reg        pos_b  [0:NK-1];
    reg [6:0]  ncols_b [0:NK-1];
    reg [3:0]  neff_b [0:NK-1];
    wire       w_cfg = we && waddr == A_CFG;
    integer b;
    always @(posedge clk) begin
        for (b = 0; b < NK; b = b + 1) begin
            if (rst) begin
                alg2_b[b]       <= 1'b0;
                pos_b[b]        <= 1'b0;
                ncols_b[b][6]   <= 1'b0;
                neff_b[b]       <= 4'd0;
            end else if (w_cfg && wk == b[KW-1:0]) begin
                alg2_b[b]       <= (wdata[14:13] == 2'd2);
                pos_b[b]        <= wdata[12];
                ncols_b[b][6]   <= wdata[6];
                neff_b[b]       <= w_ne;
            end
            if (rst || (w_cfg && wk == b[KW-1:0] && wdata[6])) ncols_b[b][5:0] <= 6'd0;
            else if (w_cfg && wk == b[KW-1:0])                  ncols_b[b][5:0] <= wdata[5:0];
        end
    end
    assign alg2  = alg2_b[rk];
    assign pos   = pos_b[rk];
    assign ncols = ncols_b[rk];
    assign neff  = neff_b[rk];
    genvar ga;
    generate for (ga = 0; ga < NAXES; ga = ga + 1) begin : g_pos
        if (AXB == 0) begin : g_1
            assign pos_v[ga] = pos_b[bank_v[ga]];
        end else begin : g_n
            localparam [AXW-1:0] GA = ga;
            assign pos_v[ga] = pos_b[{GA[AXB-1:0], bank_v[ga]}];
        end
    end endgenerate

    // ---- header block RAM: address {axis, bank, field}, read one clock ahead ----
    // hdr_field is the field of the next clock (O0 of the operand pipeline), so the registered read
    // gives the entry that an asynchronous read of the same field would give one clock later: writes
    // go to inactive banks only, so no word the core reads is written in the clock it is read (as a
    // LUT RAM it cost 4 LUT per 3 bits at 8 banks, per 6 bits at 2)
    (* ram_style = "block" *) reg [SW-1:0] m_hdr [0:8*NK-1];
    integer hi;
    initial for (hi = 0; hi < 8 * NK; hi = hi + 1) m_hdr[hi] = {SW{1'b0}};
    reg [SW-1:0] hdr_r;
    always @(posedge clk) begin
        if (w_hdr) m_hdr[{wk, h_f}] <= dd;
        hdr_r <= m_hdr[{rk, hdr_field}];
    end
    assign hdr = hdr_r;

    // ---- block memories: address {bank, column} ----
    (* ram_style = "block" *) reg [DW-1:0]  m_desc [0:NK*MAXC-1];
    (* ram_style = "block" *) reg [OPW-1:0] m_p0d [0:NK*MAXC-1];
    // p2 and p1 of a row are read at the same address: one memory {p2, p1} per row (half-word
    // writes), one RAMB8 in the 36-bit mode for one axis (two RAMB8 otherwise), a RAMB16 for four
    (* ram_style = "block" *) reg [2*OPW-1:0] m_p21d [0:NK*MAXC-1];
    (* ram_style = "block" *) reg [OPW-1:0] m_p0q [0:NK*MAXC-1];
    (* ram_style = "block" *) reg [2*OPW-1:0] m_p21q [0:NK*MAXC-1];
    (* ram_style = "block" *) reg [8:0]     m_s   [0:NK*MAXC-1];     // {s_q, 1'b0, s_d}

    always @(posedge clk) begin
        if (w_col) m_desc[wa_col] <= {wdata[CB+7:8], wdata[5:0]};
        if (w_gain && !g_row && g_k == 2'd0) m_p0d[wa_gain] <= wsat;
        if (w_gain && !g_row && g_k == 2'd1) m_p21d[wa_gain][OPW-1:0] <= wsat;
        if (w_gain && !g_row && g_k == 2'd2) m_p21d[wa_gain][2*OPW-1:OPW] <= wsat;
        if (w_gain && !g_row && g_k == 2'd3) m_s[wa_gain][3:0] <= wdata[3:0];
        if (w_gain &&  g_row && g_k == 2'd0) m_p0q[wa_gain] <= wsat;
        if (w_gain &&  g_row && g_k == 2'd1) m_p21q[wa_gain][OPW-1:0] <= wsat;
        if (w_gain &&  g_row && g_k == 2'd2) m_p21q[wa_gain][2*OPW-1:OPW] <= wsat;
        if (w_gain &&  g_row && g_k == 2'd3) m_s[wa_gain][8:5] <= wdata[3:0];
    end

    reg [8:0] s_r;
    assign s_d = s_r[3:0];
    assign s_q = s_r[8:5];
    always @(posedge clk) begin
        if (rst) begin
            desc <= {DW{1'b0}};
            p2_d <= {OPW{1'b0}}; p2_q <= {OPW{1'b0}};
            p1_d <= {OPW{1'b0}}; p1_q <= {OPW{1'b0}};
            p0_d <= {OPW{1'b0}}; p0_q <= {OPW{1'b0}};
        end else begin
            desc <= m_desc[{rk, ra_desc}];
            {p2_d, p1_d} <= m_p21d[{rk, ra_c}];
            {p2_q, p1_q} <= m_p21q[{rk, ra_c}];
            p0_d <= m_p0d[{rk, ra_p0}];
            p0_q <= m_p0q[{rk, ra_p0}];
        end
        if (rst || s_clr) s_r <= 9'd0;
        else              s_r <= m_s[{rk, ra_s}];
    end

    wire unused_ok = &{1'b0, coff[9:6], goff[9], hoff[9:3], s_r[4], waxis, raxis};
endmodule
`default_nettype wire
