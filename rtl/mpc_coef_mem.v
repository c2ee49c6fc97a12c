// mpc_coef_mem: the MPC core's two coefficient banks (image layout of gen/empc/image.py).
//
// Write port: one 32-bit image word per clock (we, wbank, waddr = word address of the
// image layout, wdata).  Decoded as it is written:
//   A_CFG        algorithm[14:13], task[12] (1 = position), N[11:8], ncols[6:0] -> registers
//   A_WS         ws[4:0];   A_WNMIN / A_WNMAX  signed 32 -> clamped to +-(2^17-1)
//   A_UMAX       unsigned 32 -> min(u_max, 2^17-1);   A_EBAR + o   ebar_lim[o], 32 bit unsigned
//   A_COLS + j   column j {shift[12:8], sig[5:0]}   -> column memory
//   A_GAINS + 4 (64 i + j) + k   row i, column j: k = 0..2 p0, p1, p2 (signed 32, saturated
//                to 18 bit), k = 3 product shift [3:0]  -> coefficient memories
//   other addresses (magic, used, checksum, unused) are ignored.
// ncols is clamped to MAX_COLS; neff3 = 3 min(N_img, N) (horizon steps the core reads).
// Read side: synchronous reads (data valid one clock after the address) of bank rbank,
// one address per memory so the core can stagger the reads along its pipeline; the
// header fields of bank rbank are combinational outputs of the bank registers.
// Storage: per bank and column 6 x 18 bit coefficients, 2 x 4 bit shifts, 11 bit column
// descriptor, each in its own simple-dual-port memory of 2 x 64 words (block RAM / LUT RAM).
// Parameters: N (horizon inputs of the core, <= EMPC_N_MAX).
// Reset: header registers of both banks clear to 0 (ncols = 0: an empty bank gives du = 0);
// the memories are not reset; read registers clear to 0.
`default_nettype none
`include "empc_formats.vh"
module mpc_coef_mem #(
    parameter integer N = `EMPC_N
) (
    input  wire                        clk,
    input  wire                        rst,
    input  wire                        we,
    input  wire                        wbank,
    input  wire [9:0]                  waddr,
    input  wire [31:0]                 wdata,
    input  wire                        rbank,
    input  wire [5:0]                  ra_desc,
    input  wire [5:0]                  ra_p2,
    input  wire [5:0]                  ra_p1,
    input  wire [5:0]                  ra_p0,
    input  wire [5:0]                  ra_s,
    output reg  [10:0]                 desc,
    output reg  signed [`EMPC_OPW-1:0] p2_d,
    output reg  signed [`EMPC_OPW-1:0] p2_q,
    output reg  signed [`EMPC_OPW-1:0] p1_d,
    output reg  signed [`EMPC_OPW-1:0] p1_q,
    output reg  signed [`EMPC_OPW-1:0] p0_d,
    output reg  signed [`EMPC_OPW-1:0] p0_q,
    output reg  [3:0]                  s_d,
    output reg  [3:0]                  s_q,
    output wire                        alg2,
    output wire                        pos,
    output wire [6:0]                  ncols,
    output wire [4:0]                  neff3,
    output wire [4:0]                  ws,
    output wire signed [`EMPC_OPW-1:0] wn_min,
    output wire signed [`EMPC_OPW-1:0] wn_max,
    output wire [`EMPC_OPW-1:0]        u_max,
    output wire [3*32-1:0]             ebar_lim
);
    localparam integer OPW   = `EMPC_OPW;
    localparam integer MAXC  = `EMPC_MAX_COLS;     // 64
    localparam integer NEFF  = (N < `EMPC_N_MAX) ? N : `EMPC_N_MAX;
    localparam [9:0] A_CFG   = `EMPC_IMG_A_CFG;
    localparam [9:0] A_WS    = `EMPC_IMG_A_WS;
    localparam [9:0] A_WNMIN = `EMPC_IMG_A_WNMIN;
    localparam [9:0] A_WNMAX = `EMPC_IMG_A_WNMAX;
    localparam [9:0] A_UMAX  = `EMPC_IMG_A_UMAX;
    localparam [9:0] A_EBAR  = `EMPC_IMG_A_EBAR;
    localparam [9:0] A_COLS  = `EMPC_IMG_A_COLS;
    localparam [9:0] A_GAINS = `EMPC_IMG_A_GAINS;
    localparam [9:0] A_GEND  = `EMPC_IMG_A_GAINS + 8 * `EMPC_MAX_COLS;
    localparam [9:0] A_CEND  = `EMPC_IMG_A_COLS + `EMPC_MAX_COLS;
    localparam [OPW-1:0] OMAX = {1'b0, {(OPW-1){1'b1}}};

    // ---- write decode ----
    wire [9:0] coff = waddr - A_COLS;
    wire [9:0] goff = waddr - A_GAINS;
    wire w_col  = we && waddr >= A_COLS  && waddr < A_CEND;
    wire w_gain = we && waddr >= A_GAINS && waddr < A_GEND;
    wire [6:0] wa_col  = {wbank, coff[5:0]};
    wire [6:0] wa_gain = {wbank, goff[7:2]};
    wire g_row = goff[8];
    wire [1:0] g_k = goff[1:0];

    // signed 32 -> sat18
    wire s_ok = (&wdata[31:OPW-1]) | ~(|wdata[31:OPW-1]);
    wire signed [OPW-1:0] wsat = s_ok ? wdata[OPW-1:0] : (wdata[31] ? ~OMAX : OMAX);
    // signed 32 -> clamp +-(2^17 - 1)
    wire signed [OPW-1:0] wclamp = (wsat == ~OMAX) ? -$signed(OMAX) : wsat;
    // unsigned 32 -> min(., 2^17 - 1)
    wire [OPW-1:0] wumax = (|wdata[31:OPW-1]) ? OMAX : {1'b0, wdata[OPW-2:0]};
    // header N / ncols
    wire [3:0] w_n   = wdata[11:8];
    wire [3:0] w_ne  = (w_n > NEFF[3:0]) ? NEFF[3:0] : w_n;
    wire [6:0] w_nc  = (wdata[6:0] > MAXC[6:0]) ? MAXC[6:0] : wdata[6:0];

    wire [2:0] eb_base = wbank ? 3'd3 : 3'd0;

    // ---- per-bank header registers ----
    reg        alg2_b [0:1];
    reg        pos_b  [0:1];
    reg [6:0]  ncols_b [0:1];
    reg [4:0]  neff3_b [0:1];
    reg [4:0]  ws_b [0:1];
    reg [OPW-1:0] wnmin_b [0:1];
    reg [OPW-1:0] wnmax_b [0:1];
    reg [OPW-1:0] umax_b [0:1];
    reg [31:0] ebl_b [0:5];          // index 3 * bank + o
    integer b;
    always @(posedge clk) begin
        if (rst) begin
            for (b = 0; b < 2; b = b + 1) begin
                alg2_b[b]  <= 1'b0;
                pos_b[b]   <= 1'b0;
                ncols_b[b] <= 7'd0;
                neff3_b[b] <= 5'd0;
                ws_b[b]    <= 5'd0;
                wnmin_b[b] <= {OPW{1'b0}};
                wnmax_b[b] <= {OPW{1'b0}};
                umax_b[b]  <= {OPW{1'b0}};
            end
            for (b = 0; b < 6; b = b + 1) ebl_b[b] <= 32'd0;
        end else if (we) begin
            if (waddr == A_CFG) begin
                alg2_b[wbank]  <= (wdata[14:13] == 2'd2);
                pos_b[wbank]   <= wdata[12];
                ncols_b[wbank] <= w_nc;
                neff3_b[wbank] <= {1'b0, w_ne} + {w_ne, 1'b0};
            end
            if (waddr == A_WS)    ws_b[wbank]    <= wdata[4:0];
            if (waddr == A_WNMIN) wnmin_b[wbank] <= wclamp;
            if (waddr == A_WNMAX) wnmax_b[wbank] <= wclamp;
            if (waddr == A_UMAX)  umax_b[wbank]  <= wumax;
            for (b = 0; b < 3; b = b + 1)
                if (waddr == A_EBAR + b[9:0]) ebl_b[eb_base + b[2:0]] <= wdata;
        end
    end
    assign alg2   = alg2_b[rbank];
    assign pos    = pos_b[rbank];
    assign ncols  = ncols_b[rbank];
    assign neff3  = neff3_b[rbank];
    assign ws     = ws_b[rbank];
    assign wn_min = wnmin_b[rbank];
    assign wn_max = wnmax_b[rbank];
    assign u_max  = umax_b[rbank];
    assign ebar_lim = rbank ? {ebl_b[5], ebl_b[4], ebl_b[3]} : {ebl_b[2], ebl_b[1], ebl_b[0]};

    // ---- memories: address {bank, column} ----
    reg [10:0]    m_desc [0:2*MAXC-1];
    reg [OPW-1:0] m_p0d [0:2*MAXC-1];
    reg [OPW-1:0] m_p1d [0:2*MAXC-1];
    reg [OPW-1:0] m_p2d [0:2*MAXC-1];
    reg [OPW-1:0] m_p0q [0:2*MAXC-1];
    reg [OPW-1:0] m_p1q [0:2*MAXC-1];
    reg [OPW-1:0] m_p2q [0:2*MAXC-1];
    reg [3:0]     m_sd  [0:2*MAXC-1];
    reg [3:0]     m_sq  [0:2*MAXC-1];

    always @(posedge clk) begin
        if (w_col) m_desc[wa_col] <= {wdata[12:8], wdata[5:0]};
        if (w_gain && !g_row && g_k == 2'd0) m_p0d[wa_gain] <= wsat;
        if (w_gain && !g_row && g_k == 2'd1) m_p1d[wa_gain] <= wsat;
        if (w_gain && !g_row && g_k == 2'd2) m_p2d[wa_gain] <= wsat;
        if (w_gain && !g_row && g_k == 2'd3) m_sd[wa_gain]  <= wdata[3:0];
        if (w_gain &&  g_row && g_k == 2'd0) m_p0q[wa_gain] <= wsat;
        if (w_gain &&  g_row && g_k == 2'd1) m_p1q[wa_gain] <= wsat;
        if (w_gain &&  g_row && g_k == 2'd2) m_p2q[wa_gain] <= wsat;
        if (w_gain &&  g_row && g_k == 2'd3) m_sq[wa_gain]  <= wdata[3:0];
    end

    always @(posedge clk) begin
        if (rst) begin
            desc <= 11'd0;
            p2_d <= {OPW{1'b0}}; p2_q <= {OPW{1'b0}};
            p1_d <= {OPW{1'b0}}; p1_q <= {OPW{1'b0}};
            p0_d <= {OPW{1'b0}}; p0_q <= {OPW{1'b0}};
            s_d  <= 4'd0;        s_q  <= 4'd0;
        end else begin
            desc <= m_desc[{rbank, ra_desc}];
            p2_d <= m_p2d[{rbank, ra_p2}];
            p2_q <= m_p2q[{rbank, ra_p2}];
            p1_d <= m_p1d[{rbank, ra_p1}];
            p1_q <= m_p1q[{rbank, ra_p1}];
            p0_d <= m_p0d[{rbank, ra_p0}];
            p0_q <= m_p0q[{rbank, ra_p0}];
            s_d  <= m_sd[{rbank, ra_s}];
            s_q  <= m_sq[{rbank, ra_s}];
        end
    end

    wire unused_ok = &{1'b0, coff[9:6], goff[9]};
endmodule
`default_nettype wire
