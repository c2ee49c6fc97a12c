// mpc_core: explicit MPC of paper 000 (eqs. 23-29) with polynomial gains, one update per start.
//
// Bit-exact to gen/empc/rtlmodel/mpc_core.py (update()): scheduling speed wn, aggregated
// error ebar (algorithm 2), operand stream, two lanes (rows d, q) evaluating the gain
// polynomials k = p0 + wn (p1 + p2 wn) and accumulating k * a << s over the image's columns,
// du, u_raw = u_prev + du and the circle voltage limiter (RSQRT table, vector scaling).
//
// Inputs: a 64 x SIG_W-bit input buffer written through in_we / in_addr / in_wdata (one word
// per clock, signed, sign-extended by the writer) before start; word map EMPC_IN_* of the
// header / IN_* of the model (y[o] at 0..2, omega 3, dx[n] 4..8, u_prev[i] 9..10,
// ebar_prev[o] 11..13, wref[m][o] at 16 + 3 m + o for m = 0..N).  The core reads the buffer
// during the update (it does not copy it): the words must not change from start to done.
// Handshake: `start` (1 cycle, accepted when ready && !busy); `busy` is high from the next
// cycle until the outputs are loaded; `done` is a 1-cycle pulse with the outputs valid;
// outputs hold until the next update's done.
// Latency: start -> done = LAT_BASE + ncols clock cycles (LAT_BASE = 38; ncols of the
// active image: 17 for algorithm 1, 23 for algorithm 2 with N = 4 -> 55 / 61 cycles),
// independent of the data (the limiter path is always traversed).  Port `latency`.
// Schedule (cycle 0 = first cycle after start; item issue at O0 of mpc_operand):
//   0..8   YC0 YC1 YC2 WN LO HI EBA0 EBA1 EBA2     (copies of y, wn and its clamp, eq. 25 inc)
//   11+j   column j (j < ncols); lanes: G1 = 12 + j, acc includes it from 19 + j
//   u = cycle - 11 - ncols:  u 5 round step (mul3 = 2^23, acc += it at u 8), u 9 du = acc[47:24];
//   u 8..15 items UR0 UR1 UMX NUMX UR0 EBB0 EBB1 EBB2; u 13.. op bus u18_d, u18_q, umax,
//   -umax, u18_d; lane d: u18_d^2, u18_q^2, -umax^2 accumulated (acc = r at u 18,
//   r - umax^2 at u 20); u 19 RSQRT address, u 20 t, mul2_d = t umax, u 22 f -> op bus,
//   u 23 mul3 = u18 f, u 25 outputs, u 26 done.
//
// Coefficient banks: two banks (mpc_coef_mem).  Bank `bank` is active (read by updates),
// the other one is written by the CPU port (cfg_we, cfg_addr = image word address,
// cfg_wdata) one word per clock, decoded as written; mpc_boot checks every upload as it is
// written (upl_ok: the inactive bank holds exactly one complete image, words 0..767 in
// order, with magic, layout, N, format fingerprint and checksum of this build, and nothing
// was written after it).  cfg_swap requests a bank swap (swap_pending); it is decided at
// the next control-period boundary, `swap_at` (a pulse from the sequencer: mx_seq's
// ctl_boundary, the PWM boundary before the next control sample), at an edge with no update
// running:
//   - accepted if upl_ok and no CPU word is in flight (cfg_we or the registered port):
//     bank flips at that edge, upl_ok clears (the new inactive bank is the old tuning,
//     not an upload), img_ok = 1, swap_refused clears;
//   - otherwise refused: bank unchanged, swap_refused = 1 (until an accepted swap) and a
//     one-clock `refused` pulse (the axis counts it).
// A request in the clock of swap_at is decided at that edge.  An update in progress always
// finishes with the bank it started with.  Writes always go to the bank that is inactive in
// the cycle of the request (a word written while a swap is pending makes it refused).
// Control period: an image records the control period its gains were designed for (CFG[23:16],
// PWM periods); a swap is also refused if the upload's period is not the axis's pwm_per_control
// (CTRL.pwm_per_control: the old tuning stays, swap_refused), and img_ok needs the active bank's
// period to equal it (a CTRL.pwm_per_control write with the bridges off that does not match the
// active image: img_ok = 0, FAULT.coef, the bridges stay off until a matching image is swapped in).
// img_ok: the active bank holds a valid image (the boot image passed the check, or an
// accepted swap) designed for the axis's control period; a bad boot image leaves img_ok = 0 until
// a valid upload is swapped in (the axis keeps the bridges off meanwhile).
// Reset: bank 0 active, the boot image (BOOT_FILE) is streamed into bank 0 through the
// same write path (mpc_boot, USED = 768 words); `ready` rises 771 cycles after rst is
// released, boot_ok = img_ok = the boot image passed the check.  start, cfg_we and
// cfg_swap are ignored while ready = 0 (the input buffer can be written at any time).
// All outputs clear to 0 at reset.
//
// Several axes (NAXES > 1, docs/four_axes.md piece 1): every axis a has its own bank pair and
// 64 input words (in_addr = {axis, word}); start[a] (one-hot) starts an update of axis a with
// its words and its active bank (axis latched for the update); cfg_addr = {axis, word} writes
// into that axis's inactive bank; cfg_swap[a], swap_at[a], bank[a], swap_pending[a], upl_ok[a],
// img_ok[a], swap_refused[a], refused[a], task_pos[a] are per axis, and axis a's swap is decided
// at swap_at[a] unless an update of axis a runs (another axis's update or in-flight word does not
// matter).  One upload at a time (a shared checker; an axis change breaks the sequence).  The
// boot image goes into bank 0 of every axis: ready (NAXES-1) * 1024 + 771 cycles after reset.
// NAXES = 1: every vector is one bit, the port list and behaviour are those of the one-axis core.
// Ports (vectors flattened, element k at [k*W +: W]):
//   in_we, in_addr[5+AXB:0], in_wdata[31:0]: input buffer write port
//   outputs u, du, u_raw [2 x 24], ebar [3 x 40], wn (Q1.17), flags
//   (bit = FLAG_BITS of the model: 0 operand, 1 gain, 2 term, 3 acc, 4 du, 5 u, 6 ebar,
//   7 ebar_inc, 8 limit, 9 wn_clamp, 10 signal: that saturation happened in this update).
//   Status: ready, bank (active), swap_pending, boot_ok, img_ok, upl_ok, swap_refused,
//   refused (pulse), task_pos (task of the active bank, 1 = position: the front end
//   selects y2 / references accordingly), latency.
//   Field weakening (model step 7): fw_thr = {lo, hi} (register FW_R2) in; fw_hi, fw_lo out,
//   loaded with the other outputs (|u_raw|^2 of the update above hi / below lo).
//   Control period: pwm_per_control[PERW*a +: PERW] = axis a's CTRL.pwm_per_control (in; img_ok and
//   the swap decision compare it with the image's CFG[23:16]).
//   Anti-windup (model step 2): aw = {i_q < 0, |i_q| >= the hold current} (mpc_axis: register IQ_HOLD,
//   0 = off; stable during an update): the speed task's speed-error increment is held while aw[0] and it
//   has the sign aw[1] (it would drive |i_q| further).
// Parameters: N (horizon inputs, default EMPC_N), NAXES (axes, 1..8; AXB = clog2(NAXES)),
// BOOT_FILE, RSQRT_FILE ($readmemh paths), PERW (control period width, EMPC_IMG_CFG_PERIOD_BITS = 8).
// Resources: 6 DSP48A1 (3 per lane, the limiter reuses them), block RAM for the boot
// ROM (1024 x 32), RSQRT (1024 x 18), the coefficient memories, the bank headers and the
// input buffer, LUT RAM for the scratch words.
`default_nettype none
`include "empc_formats.vh"
`include "mpc_items.vh"
module mpc_core #(
    parameter integer N = `EMPC_N,
    parameter integer NAXES = 1,            // axes sharing the core (1..8): a bank pair and input words each
    parameter BOOT_FILE = "coef_boot.hex",
    parameter RSQRT_FILE = "rsqrt.hex",
    parameter integer PERW = `EMPC_IMG_CFG_PERIOD_BITS  // control period field (CTRL.pwm_per_control's width)
`ifdef EMPC_SIM_GATE
    , parameter integer SIM_GATE = 1        // simulation only: 0 = clock never stopped (see "core clock")
`endif
) (
    input  wire                            clk,
    input  wire                            rst,
    // update
    input  wire [NAXES-1:0]                start,        // start[a]: an update of axis a (one-hot)
    input  wire                            in_we,
    input  wire [5+$clog2(NAXES):0]        in_addr,      // {axis, word}
    input  wire signed [`EMPC_SIG_W-1:0]   in_wdata,
    output reg                             busy,
    output reg                             done,
    output reg  [2*`EMPC_U_W-1:0]          u,
    output reg  [2*`EMPC_U_W-1:0]          du,
    output reg  [2*`EMPC_U_W-1:0]          u_raw,
    output reg  [3*`EMPC_SIG_W-1:0]        ebar,
    output reg  signed [`EMPC_OPW-1:0]     wn,
    output reg  [10:0]                     flags,
    output wire [7:0]                      latency,
    input  wire [31:0]                     fw_thr,
    output reg                             fw_hi,
    output reg                             fw_lo,
    input  wire [1:0]                      aw,
    // coefficient banks
    input  wire                            cfg_we,
    input  wire [9+$clog2(NAXES):0]        cfg_addr,     // {axis, image word}
    input  wire [31:0]                     cfg_wdata,
    input  wire [NAXES-1:0]                cfg_swap,
    input  wire [NAXES-1:0]                swap_at,      // control-period boundary of each axis (pulse)
    output wire                            ready,
    output reg  [NAXES-1:0]                bank,
    output reg  [NAXES-1:0]                swap_pending,
    output wire                            boot_ok,
    output wire [NAXES-1:0]                img_ok,       // the active bank holds a valid image
    output wire [NAXES-1:0]                upl_ok,       // the inactive bank holds a complete valid upload
    output reg  [NAXES-1:0]                swap_refused, // the last decided swap was refused
    output reg  [NAXES-1:0]                refused,      // pulse: a swap was refused
    output wire [NAXES-1:0]                task_pos,     // active bank: 1 = position task
    input  wire [PERW*NAXES-1:0]           pwm_per_control  // CTRL.pwm_per_control of every axis
);
    localparam integer AXB  = $clog2(NAXES);    // axis bits of in_addr / cfg_addr
    localparam integer AXW  = (AXB > 0) ? AXB : 1;
    localparam integer OPW  = `EMPC_OPW;
    localparam integer UW   = `EMPC_U_W;
    localparam integer SW   = `EMPC_SIG_W;
    localparam integer ACCW = `EMPC_ACCW;
    localparam integer VSH  = `EMPC_U_FRAC - `EMPC_V_FRAC;   // u = scaled value << VSH
    localparam integer T_COL = 11;            // first column item
    localparam integer NPRE  = 9;             // pre-phase items at cycles 0..8
    localparam integer NTAIL = 26;            // tail steps u = 0..25
    localparam [7:0] LAT_BASE = T_COL[7:0] + NTAIL[7:0] + 8'd1;   // start -> done = LAT_BASE + ncols

    // ---- core clock.  Simulation only (EMPC_SIM_GATE, never in synthesis): the clock stops while
    // the core is idle (no reset, boot, start, update, input or coefficient write, swap, and
    // SIM_GATE_DRAIN clocks after the last of them), which makes the RTL co-simulation about 1.35
    // times faster; the core's clock runs about 2 % of the clocks there.  Proof: tb/hdl/cosim_top.v
    // with COSIM_LOCKSTEP runs an ungated copy (SIM_GATE = 0) on the same inputs and compares every
    // output every clock (tb/test_closed_loop.py::test_closed_loop_lockstep). ----
`ifdef EMPC_SIM_GATE
    localparam [7:0] SIM_GATE_DRAIN = 8'd255;
    reg  [7:0] sim_drain;
    reg        sim_en;
    wire       sim_act = rst | (|start) | in_we | cfg_we | (|cfg_swap) | busy | (|swap_pending) | !ready | done;
    always @(posedge clk) sim_drain <= sim_act ? SIM_GATE_DRAIN : sim_drain - {7'd0, sim_drain != 8'd0};
    // changes while clk is low: no glitch on cclk
    always @(negedge clk) sim_en <= (SIM_GATE == 0) | sim_act | (sim_drain != 8'd0);
    wire       cclk = clk & sim_en;
`else
    wire       cclk = clk;
`endif
    // tail steps (u = cycles after the last column item)
    localparam integer U_RND = 5, U_UR0 = 8, U_UR1 = 9, U_DU = 9, U_UMX = 10, U_NUMX = 11, U_UR0B = 12,
                       U_EBB = 13, U_ULD0 = 12, U_M3U0 = 13, U_CLR = 14, U_ACCX = 16, U_LDR = 18,
                       U_LDLIM = 20, U_M2T = 20, U_SELF = 22, U_M3RND = 23, U_FIRE = 25;

    // ---- axes: the update's axis (latched at start), the CPU word's axis ----
    reg  [AXW-1:0] axis_r;                               // axis of the running (or last) update
    reg  [AXW-1:0] st_ax;                                // start: lowest axis whose start bit is set
    wire [AXW-1:0] cfg_ax;
    integer sa;
    always @* begin
        st_ax = {AXW{1'b0}};
        for (sa = NAXES - 1; sa >= 0; sa = sa - 1)
            if (start[sa]) st_ax = sa[AXW-1:0];
    end
    generate if (AXB == 0) begin : g_cax1
        assign cfg_ax = 1'b0;
    end else begin : g_caxn
        assign cfg_ax = cfg_addr[9+AXB:10];
    end endgenerate

    // ---- write port (registered): boot stream (every axis), then the CPU; a CPU word goes to
    // its axis's bank that is inactive in the cycle of the request ----
    wire        w_we;
    wire [AXW-1:0] w_ax;
    wire [9:0]  w_addr;
    wire [31:0] w_data;
    wire        ready_r;
    reg         w_bank;
    assign ready = ready_r;
    reg  [NAXES-1:0] swap_go;                            // axis a's swap is applied at this edge
    wire             boot_ok_n;                          // boot_ok at the next edge
    mpc_boot #(.BOOT_FILE(BOOT_FILE), .N(N), .NAXES(NAXES), .AXW(AXW)) u_boot (
        .clk(cclk), .rst(rst), .cfg_we(cfg_we), .cfg_axis(cfg_ax), .cfg_addr(cfg_addr[9:0]),
        .cfg_wdata(cfg_wdata), .ok_clr(swap_go),
        .we(w_we), .wax(w_ax), .addr(w_addr), .data(w_data), .ready(ready_r), .ok(boot_ok), .ok_next(boot_ok_n),
        .upl_ok(upl_ok)
    );
    always @(posedge cclk) begin
        if (rst) w_bank <= 1'b0;
        else     w_bank <= ready_r & ~bank[cfg_ax];
    end

    // ---- control periods (image CFG[23:16], PWM periods per control period the gains are for), per
    // axis: upl_per = the last CFG word written into the axis's inactive bank (the boot stream's too),
    // act_per = the active bank's (upl_per while booting; upl_per at an accepted swap).  A swap is
    // accepted only if the upload's period is the axis's pwm_per_control, and img_ok needs the active
    // bank's period to be it (CTRL.pwm_per_control changes only with the bridges off) ----
    localparam [9:0] A_CFG = `EMPC_IMG_A_CFG;
    localparam integer PER_LSB = `EMPC_IMG_CFG_PERIOD_LSB;
    reg  [PERW-1:0] upl_per [0:NAXES-1];
    reg  [PERW-1:0] act_per [0:NAXES-1];
    wire            w_cfg = w_we && (w_addr == A_CFG);
    integer pa;
    always @(posedge cclk) begin
        for (pa = 0; pa < NAXES; pa = pa + 1) begin
            if (rst) begin
                upl_per[pa] <= {PERW{1'b0}};
                act_per[pa] <= {PERW{1'b0}};
            end else begin
                if (w_cfg && w_ax == pa[AXW-1:0]) upl_per[pa] <= w_data[PER_LSB +: PERW];
                if (!ready_r || swap_go[pa])      act_per[pa] <= upl_per[pa];
            end
        end
    end

    // ---- bank swap decisions, per axis: at the axis's boundary, with no update of that axis running ----
    reg  [NAXES-1:0] swap_dec;
    integer xa;
    always @(*) begin
        for (xa = 0; xa < NAXES; xa = xa + 1) begin
            swap_dec[xa] = ready_r && (swap_pending[xa] || cfg_swap[xa]) && swap_at[xa] &&
                           !(busy && axis_r == xa[AXW-1:0]);
            swap_go[xa]  = swap_dec[xa] && upl_ok[xa] && !(cfg_we && cfg_ax == xa[AXW-1:0]) &&
                           !(w_we && w_ax == xa[AXW-1:0]) &&
                           (upl_per[xa] == pwm_per_control[PERW*xa +: PERW]);
        end
    end
    // img_val = boot_ok | (a swap was accepted since reset): every accepted swap brings a valid image.
    // Both parts only rise (boot_ok once, at the end of the boot stream), so the register takes
    // boot_ok's next value, its own value and this edge's swaps (the gate boot_ok | swapped after the
    // flip-flops made the kill path the drive's worst path, 10 LUT levels).
    // img_ok = img_val and the active bank's period is the axis's pwm_per_control, in the same clock
    // (a CTRL write may change pwm_per_control and set enable at once: a registered compare would be a
    // clock late); the compare is one 2 x PERW-input equality of two flip-flop vectors
    reg  [NAXES-1:0] img_val_r;
    always @(posedge cclk) begin
        if (rst) img_val_r <= {NAXES{1'b0}};
        else     img_val_r <= {NAXES{boot_ok_n}} | img_val_r | swap_go;
    end
    genvar gp;
    generate for (gp = 0; gp < NAXES; gp = gp + 1) begin : g_per
        assign img_ok[gp] = img_val_r[gp] && (act_per[gp] == pwm_per_control[PERW*gp +: PERW]);
    end endgenerate

    // ---- sequencing: one-hot pre-phase and tail, column counter ----
    wire start_ok = (|start) && ready_r && !busy;
    reg  [NPRE+1:0]  pre;         // pre[k]: cycle k (k = 0 .. T_COL-1)
    reg  [NTAIL-1:0] tl;          // tl[u]: tail step u
    reg              col_run;
    reg  [5:0]       jc;          // column at O0; all ones when no column runs
    wire [6:0]       ncols;
    wire [6:0]       jn = {1'b0, jc} + 7'd1;     // next column; [5:0] = 0 when idle: descriptor read address
    wire             last_col = col_run && (jn == ncols);
    // next state of the sequencer
    wire [NPRE+1:0]  pre_n  = {pre[NPRE:0], start_ok};
    wire             tail_go = last_col || (pre[T_COL-1] && ncols == 7'd0);
    wire [NTAIL-1:0] tl_n   = {tl[NTAIL-2:0], tail_go};
    wire             col_n  = (pre[T_COL-1] && ncols != 7'd0) || (col_run && !last_col);
    reg  [6:1]       colv;        // column token at O1..O6
    reg  [5:0]       j1, j2, j3, j4, j5, j6;
    assign latency = LAT_BASE + {1'b0, ncols};

    always @(posedge cclk) begin
        if (rst) begin
            busy <= 1'b0;
            pre <= {(NPRE+2){1'b0}};
            tl <= {NTAIL{1'b0}};
            col_run <= 1'b0;
            colv <= 6'd0;
            j1 <= 6'd0; j2 <= 6'd0; j3 <= 6'd0; j4 <= 6'd0; j5 <= 6'd0; j6 <= 6'd0;
            axis_r <= {AXW{1'b0}};
            bank <= {NAXES{1'b0}};
            swap_pending <= {NAXES{1'b0}};
            swap_refused <= {NAXES{1'b0}};
            refused <= {NAXES{1'b0}};
        end else begin
            pre <= pre_n;
            tl <= tl_n;
            if (pre[T_COL-1] && ncols != 7'd0) col_run <= 1'b1;
            else if (last_col)                  col_run <= 1'b0;
            colv <= {colv[5:1], col_run};
            {j6, j5, j4, j3, j2, j1} <= {j5, j4, j3, j2, j1, jc};
            if (start_ok) busy <= 1'b1;
            else if (tl[U_FIRE]) busy <= 1'b0;
            if (start_ok) axis_r <= st_ax;
            // bank swaps: decided at the axis's control-period boundary, with no update of it running
            refused <= swap_dec & ~swap_go;
            for (xa = 0; xa < NAXES; xa = xa + 1) begin
                if (swap_dec[xa]) begin
                    swap_pending[xa] <= 1'b0;
                    swap_refused[xa] <= !swap_go[xa];
                end else if (cfg_swap[xa] && ready_r) begin
                    swap_pending[xa] <= 1'b1;
                end
                if (swap_go[xa]) bank[xa] <= ~bank[xa];
            end
        end
    end

    // column counter: counts from all ones (idle) through 0 .. ncols-1 back to all ones (set)
    always @(posedge cclk) begin
        if (rst || !col_n) jc <= 6'h3f;
        else               jc <= jn[5:0];
    end

    // item token at O0, registered: decoded from the next state of the one-hot sequencer (the
    // item slots never overlap, so the token is an OR of the slots' codes)
    wire i_yc  = |pre_n[2:0];
    wire i_eba = |pre_n[8:6];
    wire i_ur  = tl_n[U_UR0] | tl_n[U_UR1] | tl_n[U_UR0B];
    wire i_ebb = |tl_n[U_EBB+2:U_EBB];
    reg  [3:0] kind0;
    reg  [1:0] idx0;
    wire [3:0] kind_n = ({4{i_yc}} & `MPC_K_YC) | ({4{pre_n[3]}} & `MPC_K_WN) | ({4{pre_n[4]}} & `MPC_K_LO) |
                        ({4{pre_n[5]}} & `MPC_K_HI) | ({4{i_eba}} & `MPC_K_EBA) | ({4{col_n}} & `MPC_K_COL) |
                        ({4{i_ur}} & `MPC_K_UR) | ({4{tl_n[U_UMX]}} & `MPC_K_UMX) |
                        ({4{tl_n[U_NUMX]}} & `MPC_K_NUMX) | ({4{i_ebb}} & `MPC_K_EBB);
    wire [1:0] idx_n  = {pre_n[2] | pre_n[8] | tl_n[U_EBB+2], pre_n[1] | pre_n[7] | tl_n[U_EBB+1] | tl_n[U_UR1]};
    always @(posedge cclk) begin
        if (rst) begin
            kind0 <= `MPC_K_NONE;
            idx0  <= 2'd0;
        end else begin
            kind0 <= kind_n;
            idx0  <= idx_n;
        end
    end

    // ---- coefficient banks ----
    wire [`EMPC_SIG_SHIFT_BITS+5:0] desc;
    wire signed [OPW-1:0] p2_d, p2_q, p1_d, p1_q, p0_d, p0_q;
    wire [3:0] s_d, s_q;
    wire alg2, pos;
    wire [3:0] neff;
    wire [2:0] hdr_field;
    wire signed [SW-1:0] hdr;
    mpc_coef_mem #(.N(N), .NAXES(NAXES), .AXW(AXW)) u_mem (
        .clk(cclk), .rst(rst),
        .we(w_we), .waxis(w_ax), .wbank(w_bank), .waddr(w_addr), .wdata(w_data),
        .raxis(axis_r), .rbank(bank[axis_r]), .bank_v(bank), .pos_v(task_pos), .ra_desc(jn[5:0]), .ra_c(jc), .ra_p0(j2), .ra_s(j6), .s_clr(!colv[6]),
        .desc(desc), .p2_d(p2_d), .p2_q(p2_q), .p1_d(p1_d), .p1_q(p1_q), .p0_d(p0_d), .p0_q(p0_q),
        .s_d(s_d), .s_q(s_q),
        .alg2(alg2), .pos(pos), .ncols(ncols), .neff(neff), .hdr_field(hdr_field), .hdr(hdr)
    );

    // ---- lanes ----
    wire signed [ACCW-1:0] prod2_d, prod2_q, acc_d, acc_q;
    wire signed [UW-VSH-1:0] ul_d, ul_q;                       // scaled u >> VSH (or u_raw >> VSH)
    wire signed [OPW-1:0] op, op_next, wn_c, wn_s, lim_t, lim_f;
    wire fg_d, ft_d, fa_d, fd_d, fg_q, ft_q, fa_q, fd_q;
    wire m3u = |tl[U_M3RND:U_M3U0];
    // limiter inactive: mul3 passes u_raw (u = lim ? scaled : u_raw without a multiplexer)
    wire lim, fwh, fwl;
    wire m3ur = tl[U_M3RND] & ~lim;
    wire signed [UW-1:0] ur_d, ur_q;
    mpc_lane u_lane_d (
        .clk(cclk), .rst(rst), .clr(start_ok), .wn(wn_c), .cv(colv[1]),
        .p2(p2_d), .p1(p1_d), .p0(p0_d), .a(op), .a_next(op_next), .s(s_d),
        .rnd(tl[U_RND]), .acc_clr(tl[U_CLR]), .acc_x(tl[U_ACCX] | tl[U_ACCX+1] | tl[U_ACCX+3]),
        .m2_t(tl[U_M2T]), .t(lim_t),
        .u_ld(tl[U_ULD0] | tl[U_ULD0+1] | tl[U_ULD0+2] | tl[U_ULD0+4]), .m3_u(m3u), .m3_rnd(tl[U_M3RND]),
        .m3_ur(m3ur), .ur(ur_d),
        .prod2(prod2_d), .acc(acc_d), .u_lim(ul_d),
        .f_gain(fg_d), .f_term(ft_d), .f_acc(fa_d), .f_du(fd_d), .f_or(3'b000)
    );
    mpc_lane u_lane_q (
        .clk(cclk), .rst(rst), .clr(start_ok), .wn(wn_c), .cv(colv[1]),
        .p2(p2_q), .p1(p1_q), .p0(p0_q), .a(op), .a_next(op_next), .s(s_q),
        .rnd(tl[U_RND]), .acc_clr(1'b0), .acc_x(1'b0),
        .m2_t(1'b0), .t(lim_t),
        .u_ld(tl[U_ULD0+1]), .m3_u(m3u), .m3_rnd(tl[U_M3RND]), .m3_ur(m3ur), .ur(ur_q),
        .prod2(prod2_q), .acc(acc_q), .u_lim(ul_q),
        .f_gain(fg_q), .f_term(ft_q), .f_acc(fa_q), .f_du(fd_q), .f_or({fd_d, fa_d, ft_d})
    );
    wire signed [UW-1:0] dun_d = acc_d[ACCW-1:ACCW-UW];       // du after the round step
    wire signed [UW-1:0] dun_q = acc_q[ACCW-1:ACCW-UW];

    // ---- operand ALU ----
    wire [3*SW-1:0] ebar_c;
    wire f_signal, f_operand, f_wn, f_ebar, f_ebar_inc, f_u;
    mpc_operand #(.NAXES(NAXES), .AXW(AXW)) u_op (
        .clk(cclk), .rst(rst), .clr(start_ok),
        .in_we(in_we), .in_addr(in_addr), .raxis(axis_r), .in_wdata(in_wdata),
        .kind(kind0), .idx(idx0), .desc(desc), .alg2(alg2), .pos(pos), .aw(aw), .neff(neff),
        .hdr_field(hdr_field), .hdr(hdr), .du_d(dun_d), .du_q(dun_q), .sel_f(tl[U_SELF]), .f(lim_f),
        .op_next(op_next), .op(op), .wn(wn_c), .wn_s(wn_s), .ur_d(ur_d), .ur_q(ur_q), .ebar_s(ebar_c),
        .f_signal(f_signal), .f_operand(f_operand), .f_wn(f_wn), .f_ebar(f_ebar), .f_ebar_inc(f_ebar_inc),
        .f_u(f_u)
    );

    // ---- limiter ----
    mpc_limiter #(.RSQRT_FILE(RSQRT_FILE)) u_lim (
        .clk(cclk), .rst(rst), .acc(acc_d), .ld_r(tl[U_LDR]), .ld_lim(tl[U_LDLIM]), .ut(prod2_d),
        .fw_thr_hi(fw_thr[15:0]), .fw_thr_lo(fw_thr[31:16]), .fw_hi(fwh), .fw_lo(fwl),
        .lim(lim), .t(lim_t), .f(lim_f)
    );

    // ---- outputs ----
    reg [2*UW-1:0] du_s;
    always @(posedge cclk) begin
        if (rst) begin
            done  <= 1'b0;
            du_s  <= {(2*UW){1'b0}};
            u     <= {(2*UW){1'b0}};
            du    <= {(2*UW){1'b0}};
            u_raw <= {(2*UW){1'b0}};
            ebar  <= {(3*SW){1'b0}};
            wn    <= {OPW{1'b0}};
            flags <= 11'd0;
            fw_hi <= 1'b0;
            fw_lo <= 1'b0;
        end else begin
            if (tl[U_DU]) du_s <= {dun_q, dun_d};
            done <= tl[U_FIRE];
            if (tl[U_FIRE]) begin
                u     <= {ul_q, ur_q[VSH-1:0], ul_d, ur_d[VSH-1:0]};
                du    <= du_s;
                u_raw <= {ur_q, ur_d};
                ebar  <= ebar_c;
                wn    <= wn_s;
                flags <= {f_signal, f_wn, lim, f_ebar_inc, f_ebar, f_u, fd_q,      // fd/fa/ft_q include lane d's
                          fa_q, ft_q, fg_d | fg_q, f_operand};
                fw_hi <= fwh;
                fw_lo <= fwl;
            end
        end
        // scaled u (lim): its low VSH bits are 0 (flip-flop reset), else those of u_raw
        if (rst || (tl[U_FIRE] && lim)) begin
            u[VSH-1:0]       <= {VSH{1'b0}};
            u[UW +: VSH]     <= {VSH{1'b0}};
        end
    end

    wire unused_ok = &{1'b0, prod2_q, acc_q[ACCW-UW-1:0]};
endmodule
`default_nettype wire
