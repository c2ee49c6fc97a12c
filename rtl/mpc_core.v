// mpc_core: explicit MPC of paper 000 (eqs. 23-29) with polynomial gains, one update per start.
//
// Bit-exact to gen/empc/rtlmodel/mpc_core.py (update()): scheduling speed wn, aggregated
// error ebar (algorithm 2), operand stream, two lanes (rows d, q) evaluating the gain
// polynomials k = p0 + wn (p1 + p2 wn) and accumulating k * a << s over the image's columns,
// du, u_raw = u_prev + du and the circle voltage limiter (RSQRT table, vector scaling).
//
// Handshake: `start` (1 cycle, accepted when ready && !busy) registers all inputs; `busy`
// is high from the next cycle until the outputs are loaded; `done` is a 1-cycle pulse
// with the outputs valid; outputs hold until the next update's done.
// Latency: start -> done = LAT_BASE + ncols clock cycles (LAT_BASE = 30; ncols of the
// active image: 17 for algorithm 1, 23 for algorithm 2 with N = 4 -> 47 / 53 cycles),
// independent of the data (the limiter path is always traversed).  Port `latency`.
// Schedule (cycle 0 = first cycle after start): item WN at 0, EB0..2 at 1..3, column j
// at 7 + j (operand pipeline O0..O5, gain pipeline G0 = O0 + 1 .. G8), acc final at
// c = 16 + ncols, du c, u_raw c+1, squares c+2..c+4, limiter c+4..c+10, u c+12, done c+13.
//
// Coefficient banks: two banks (mpc_coef_mem).  Bank `bank` is active (read by updates),
// the other one is written by the CPU port (cfg_we, cfg_addr = image word address,
// cfg_wdata) one word per clock, decoded as written.  cfg_swap requests a bank swap: it
// is applied at the first clock edge at which no update is running (an update in
// progress always finishes with the bank it started with; a swap requested in the same
// cycle as an accepted start applies to that update); swap_pending is high meanwhile.
// Writes always go to the bank that is inactive in that cycle: after cfg_swap wait for
// swap_pending = 0 before writing the next tuning.
// Reset: bank 0 active, the boot image (BOOT_FILE) is streamed into bank 0 through the
// same write path (mpc_boot, USED = 768 words); `ready` rises 771 cycles after rst is
// released, boot_ok = magic and checksum of the boot image correct.  start, cfg_we and
// cfg_swap are ignored while ready = 0.  All outputs clear to 0 at reset.
//
// Ports (vectors flattened, element k at [k*W +: W]):
//   y0, y1 (i_d, i_q, Q14.4, 18 bit), y2 (speed Q16.16 or angle Q32.8, 40 bit), omega (Q16.16)
//   dx[5 x 40], wref[(N+1) x 3 x 40] (index 3 m + o, m = 0: w_k), u_prev[2 x 24] (Q16.8),
//   ebar_prev[3 x 40]; outputs u, du, u_raw [2 x 24], ebar [3 x 40], wn (Q1.17), flags
//   (bit = FLAG_BITS of the model: 0 operand, 1 gain, 2 term, 3 acc, 4 du, 5 u, 6 ebar,
//   7 ebar_inc, 8 limit, 9 wn_clamp, 10 signal: that saturation happened in this update).
//   Status: ready, bank (active), swap_pending, boot_ok, task_pos (task of the active bank,
//   1 = position: the front end selects y2 / references accordingly), latency.
// Parameters: N (horizon inputs, default EMPC_N), BOOT_FILE, RSQRT_FILE ($readmemh paths).
// Resources: 6 DSP48A1 (3 per lane, the limiter reuses them), block RAM for the boot
// ROM (1024 x 32), RSQRT (1024 x 18) and the coefficient memories.
`default_nettype none
`include "empc_formats.vh"
module mpc_core #(
    parameter integer N = `EMPC_N,
    parameter BOOT_FILE = "coef_boot.hex",
    parameter RSQRT_FILE = "rsqrt.hex"
) (
    input  wire                            clk,
    input  wire                            rst,
    // update
    input  wire                            start,
    input  wire signed [`EMPC_OPW-1:0]     y0,
    input  wire signed [`EMPC_OPW-1:0]     y1,
    input  wire signed [`EMPC_SIG_W-1:0]   y2,
    input  wire signed [`EMPC_W_W-1:0]     omega,
    input  wire [5*`EMPC_SIG_W-1:0]        dx,
    input  wire [(N+1)*3*`EMPC_SIG_W-1:0]  wref,
    input  wire [2*`EMPC_U_W-1:0]          u_prev,
    input  wire [3*`EMPC_SIG_W-1:0]        ebar_prev,
    output reg                             busy,
    output reg                             done,
    output reg  [2*`EMPC_U_W-1:0]          u,
    output reg  [2*`EMPC_U_W-1:0]          du,
    output reg  [2*`EMPC_U_W-1:0]          u_raw,
    output reg  [3*`EMPC_SIG_W-1:0]        ebar,
    output reg  signed [`EMPC_OPW-1:0]     wn,
    output reg  [10:0]                     flags,
    output wire [7:0]                      latency,
    // coefficient banks
    input  wire                            cfg_we,
    input  wire [9:0]                      cfg_addr,
    input  wire [31:0]                     cfg_wdata,
    input  wire                            cfg_swap,
    output wire                            ready,
    output reg                             bank,
    output reg                             swap_pending,
    output wire                            boot_ok,
    output wire                            task_pos      // active bank: 1 = position task
);
    localparam integer OPW = `EMPC_OPW;
    localparam integer UW  = `EMPC_U_W;
    localparam integer SW  = `EMPC_SIG_W;
    localparam [7:0] LAT_BASE = 8'd30;       // start -> done = LAT_BASE + ncols
    localparam [7:0] T_COL    = 8'd7;        // first column item
    localparam [7:0] T_FIN    = 8'd16;       // acc final at T_FIN + ncols
    localparam [1:0] K_NONE = 2'd0, K_COL = 2'd1, K_WN = 2'd2, K_EB = 2'd3;

    // ---- boot stream and write port ----
    wire        b_we;
    wire [9:0]  b_addr;
    wire [31:0] b_data;
    wire        b_done;
    mpc_boot #(.BOOT_FILE(BOOT_FILE)) u_boot (
        .clk(clk), .rst(rst), .we(b_we), .addr(b_addr), .data(b_data), .done(b_done), .ok(boot_ok)
    );
    reg ready_r;
    assign ready = ready_r;
    wire        w_we   = ready_r ? cfg_we : b_we;
    wire [9:0]  w_addr = ready_r ? cfg_addr : b_addr;
    wire [31:0] w_data = ready_r ? cfg_wdata : b_data;
    wire        w_bank = ready_r ? ~bank : 1'b0;

    // ---- control ----
    wire start_ok = start && ready_r && !busy;
    reg  [7:0] t;
    reg  [12:1] ls;              // ls[k]: fin delayed by k cycles
    wire [6:0] ncols;
    wire [7:0] ncols8 = {1'b0, ncols};
    wire fin = busy && (t == T_FIN + ncols8);
    assign latency = LAT_BASE + ncols8;

    // item token at O0
    wire [7:0] tc = t - T_COL;
    wire is_col = busy && (t >= T_COL) && (tc < ncols8);
    wire [1:0] kind0 = !busy ? K_NONE : (t == 8'd0) ? K_WN :
                       (t >= 8'd1 && t <= 8'd3) ? K_EB : is_col ? K_COL : K_NONE;
    wire [1:0] eo0 = t[1:0] - 2'd1;
    wire [5:0] j0 = tc[5:0];
    reg  [5:0] j1, j2, j3, j4, j5, j6, j7;
    reg        cv1, cv2;

    always @(posedge clk) begin
        if (rst) begin
            ready_r <= 1'b0;
            busy <= 1'b0;
            t <= 8'd0;
            ls <= 12'd0;
            bank <= 1'b0;
            swap_pending <= 1'b0;
            j1 <= 6'd0; j2 <= 6'd0; j3 <= 6'd0; j4 <= 6'd0; j5 <= 6'd0; j6 <= 6'd0; j7 <= 6'd0;
            cv1 <= 1'b0; cv2 <= 1'b0;
        end else begin
            if (b_done) ready_r <= 1'b1;
            ls <= {ls[11:1], fin};
            {j7, j6, j5, j4, j3, j2, j1} <= {j6, j5, j4, j3, j2, j1, j0};
            cv1 <= is_col;
            cv2 <= cv1;
            if (start_ok) begin
                busy <= 1'b1;
                t <= 8'd0;
            end else if (busy) begin
                t <= t + 8'd1;
                if (ls[12]) busy <= 1'b0;
            end
            // bank swap: applied at an edge with no update running
            if (!busy && ready_r && (swap_pending || cfg_swap)) begin
                bank <= ~bank;
                swap_pending <= 1'b0;
            end else if (cfg_swap && ready_r) begin
                swap_pending <= 1'b1;
            end
        end
    end

    // ---- coefficient banks ----
    wire [10:0] desc;
    wire signed [OPW-1:0] p2_d, p2_q, p1_d, p1_q, p0_d, p0_q;
    wire [3:0] s_d, s_q;
    wire alg2, pos;
    assign task_pos = pos;
    wire [4:0] neff3, ws;
    wire signed [OPW-1:0] wn_min, wn_max;
    wire [OPW-1:0] u_max;
    wire [3*32-1:0] ebar_lim;
    mpc_coef_mem #(.N(N)) u_mem (
        .clk(clk), .rst(rst),
        .we(w_we), .wbank(w_bank), .waddr(w_addr), .wdata(w_data),
        .rbank(bank), .ra_desc(j0), .ra_p2(j1), .ra_p1(j3), .ra_p0(j5), .ra_s(j7),
        .desc(desc), .p2_d(p2_d), .p2_q(p2_q), .p1_d(p1_d), .p1_q(p1_q), .p0_d(p0_d), .p0_q(p0_q),
        .s_d(s_d), .s_q(s_q),
        .alg2(alg2), .pos(pos), .ncols(ncols), .neff3(neff3), .ws(ws),
        .wn_min(wn_min), .wn_max(wn_max), .u_max(u_max), .ebar_lim(ebar_lim)
    );

    // ---- operand stream, wn, ebar ----
    wire signed [OPW-1:0] op, wn_c;
    wire [3*SW-1:0] ebar_c;
    wire f_signal, f_operand, f_wn, f_ebar, f_ebar_inc;
    mpc_operand #(.N(N)) u_op (
        .clk(clk), .rst(rst), .cap(start_ok),
        .y0(y0), .y1(y1), .y2(y2), .omega(omega), .dx(dx), .wref(wref), .ebar_prev(ebar_prev),
        .alg2(alg2), .pos(pos), .neff3(neff3), .ws(ws), .wn_min(wn_min), .wn_max(wn_max),
        .ebar_lim(ebar_lim), .kind(kind0), .eo(eo0), .desc(desc),
        .op(op), .wn(wn_c), .ebar(ebar_c),
        .f_signal(f_signal), .f_operand(f_operand), .f_wn(f_wn), .f_ebar(f_ebar), .f_ebar_inc(f_ebar_inc)
    );

    reg [2*UW-1:0] up_r;
    always @(posedge clk) begin
        if (rst) up_r <= {(2*UW){1'b0}};
        else if (start_ok) up_r <= u_prev;
    end

    // ---- lanes ----
    wire signed [2*OPW-1:0] prod1_d, prod3_d, prod1_q, prod3_q;
    wire signed [UW-1:0] du_d, du_q, ur_d, ur_q, ul_d, ul_q;
    wire fg_d, ft_d, fa_d, fd_d, fu_d, fg_q, ft_q, fa_q, fd_q, fu_q;
    wire signed [OPW-1:0] lim_t, lim_f;
    wire lim;
    wire m1_aux = ls[2] | ls[7];
    wire signed [OPW-1:0] umax_s = u_max;               // <= 2^17 - 1: positive
    wire signed [OPW-1:0] m1_b = ls[7] ? lim_t : umax_s;
    wire signed [UW-1:0] up_d = up_r[0 +: UW];
    wire signed [UW-1:0] up_q = up_r[UW +: UW];
    mpc_lane u_lane_d (
        .clk(clk), .rst(rst), .clr(start_ok), .wn(wn_c), .cv(cv2),
        .p2(p2_d), .p1(p1_d), .p0(p0_d), .a(op), .s(s_d),
        .m1_aux(m1_aux), .m1_a(umax_s), .m1_b(m1_b),
        .m3_sq(ls[2]), .m3_scale(ls[10]), .f(lim_f),
        .ld_du(fin), .ld_u(ls[1]), .u_prev(up_d),
        .prod1(prod1_d), .prod3(prod3_d), .du(du_d), .u_raw(ur_d), .u_lim(ul_d),
        .f_gain(fg_d), .f_term(ft_d), .f_acc(fa_d), .f_du(fd_d), .f_u(fu_d)
    );
    mpc_lane u_lane_q (
        .clk(clk), .rst(rst), .clr(start_ok), .wn(wn_c), .cv(cv2),
        .p2(p2_q), .p1(p1_q), .p0(p0_q), .a(op), .s(s_q),
        .m1_aux(1'b0), .m1_a({OPW{1'b0}}), .m1_b({OPW{1'b0}}),
        .m3_sq(ls[2]), .m3_scale(ls[10]), .f(lim_f),
        .ld_du(fin), .ld_u(ls[1]), .u_prev(up_q),
        .prod1(prod1_q), .prod3(prod3_q), .du(du_q), .u_raw(ur_q), .u_lim(ul_q),
        .f_gain(fg_q), .f_term(ft_q), .f_acc(fa_q), .f_du(fd_q), .f_u(fu_q)
    );

    // ---- limiter ----
    mpc_limiter #(.RSQRT_FILE(RSQRT_FILE)) u_lim (
        .clk(clk), .rst(rst), .go(ls[4]), .sq_d(prod3_d), .sq_q(prod3_q), .usq(prod1_d),
        .ut(prod1_d), .lim(lim), .t(lim_t), .f(lim_f)
    );

    // ---- outputs ----
    always @(posedge clk) begin
        if (rst) begin
            done  <= 1'b0;
            u     <= {(2*UW){1'b0}};
            du    <= {(2*UW){1'b0}};
            u_raw <= {(2*UW){1'b0}};
            ebar  <= {(3*SW){1'b0}};
            wn    <= {OPW{1'b0}};
            flags <= 11'd0;
        end else begin
            done <= ls[12];
            if (ls[12]) begin
                u     <= lim ? {ul_q, ul_d} : {ur_q, ur_d};
                du    <= {du_q, du_d};
                u_raw <= {ur_q, ur_d};
                ebar  <= ebar_c;
                wn    <= wn_c;
                flags <= {f_signal, f_wn, lim, f_ebar_inc, f_ebar, fu_d | fu_q, fd_d | fd_q,
                          fa_d | fa_q, ft_d | ft_q, fg_d | fg_q, f_operand};
            end
        end
    end

    wire unused_ok = &{1'b0, prod1_q, tc[7:6]};
endmodule
`default_nettype wire
