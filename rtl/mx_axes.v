// mx_axes: NAXES (2..4) motor axes of the explicit-MPC drive on one shared control engine
// (docs/four_axes.md 1.2, piece 5 integration; docs/blocks/mx_axes.md).
//
// Shared, one instance each with NAXES: the sequencer mx_seq (one job at a time, the job's axis on
// job_axis), mpc_core (a bank pair and input words per axis), ref_gen (slots {axis, slot}, per-axis
// strobes), axis_status (status words and counters {axis, word}) and adc_spi (one SCLK / CS / frame
// grid for 3 x NAXES converters, per-axis windows at the carrier stagger).
// Per axis (generate loop g_ax): one axis_periph (rtl/axis_periph.v, the module mpc_axis uses too, so
// the per-axis rules live in one place and formal/axis_periph.sby covers every axis): irc_decoder,
// hall_decoder, pos_sense, sens_check, fault_ctrl, pwm_center with PHASE = n x EMPC_PWM_STAGGER_<NAXES>,
// the axis's generated axis_regs (the LUT-RAM {axis, reg} block of piece 3 is a later step) and the
// glue (bridges, field weakening, governor hold, reference sync, counters, DC link, stall, causes).
// Here: the registers the engine reads (KDC, KACC, shifts, ID_REF with the field-weakening steps fw_n,
// IQ_REF, the field-weakening thresholds) multiplexed at mx_seq's job_axis, the effective ID_REF formed
// once from the job axis's ID_REF and fw_n; the core's single done / flags /
// fw_hi / fw_lo / i_q / omega belong to the job's axis (axis a gets core_done && job_axis == a, and
// the omega held while its job is not running).
// pos_sense stays per axis (NAXES = 1, THETA_LAT = 4 exact): mx_seq latches the angle a fixed
// THETA_LAT clocks after the trigger, while the shared pos_sense's theta lags a count by 8..168 clk
// and must be taken with its theta_ok (docs/blocks/pos_sense.md); the handshake is not in mx_seq yet.
//
// Register port: reg_addr = {axis, word offset}, coef_addr = {axis, image word}; reg_rdata valid one
// clock after reg_rd, 0 otherwise: one shared read path (generated rtl/axis_rd.v) takes each live value
// from the read axis's axis_regs.rd_vals export through gated copies and reads the stored registers back
// from a write-through block RAM {axis, word} written at the axes' accepted writes (axis_regs.sh_we;
// the axes' own copies are not kept).
// Safety, per axis (axis_periph's, as mpc_axis): every cause in that axis's FAULT_MASK forces that axis's
// six outputs off in the clock the cause is registered (its fault_ctrl.trip into its pwm_center);
// the watchdog, overrun / stall, power-stage, clock and coefficient-image causes trip whatever
// FAULT_MASK says; an axis's bridges are enabled only while its angle is valid and its active
// coefficient bank holds a valid image and (route_ok, lx_rocon_top: out_route's mapped = 0b111) all three
// of its phases drive an output.  A fault of axis a acts on a's pins only; ext_fault and the
// watchdog act on every axis (they are inputs of every axis's fault_ctrl).
// Parameters: NAXES (2..4; NAXES = 1 is mpc_axis), COMPLEMENTARY, HALL_DEBOUNCE, ENC_FILTER as mpc_axis.
// Reset: every CTRL.enable = 0 (outputs off), registers at their map reset values.
`default_nettype none
`include "empc_formats.vh"
`include "empc_regs.vh"
module mx_axes #(
    parameter integer NAXES = 2,
    parameter integer N = `EMPC_N,
    parameter BOOT_FILE = "coef_boot.hex",
    parameter RSQRT_FILE = "rsqrt.hex",
    parameter integer HALL_DEBOUNCE = 1000,
    parameter integer ENC_FILTER = 8,
    parameter integer COMPLEMENTARY = 0,
    parameter integer AXB = (NAXES < 2) ? 1 : $clog2(NAXES)     // axis bits (derived)
) (
    input  wire                 clk,
    input  wire                 rst,
    // CPU register port ({axis, axis-local word offset})
    input  wire                 reg_wr,
    input  wire                 reg_rd,
    input  wire [AXB+7:0]       reg_addr,
    input  wire [31:0]          reg_wdata,
    output wire [31:0]          reg_rdata,
    input  wire                 coef_we,
    input  wire [AXB+9:0]       coef_addr,
    // global
    input  wire                 watchdog_expired,
    input  wire                 g_wr_refused,
    input  wire [1:0]           ext_fault,       // {clock, pstage}: out_kill causes (every axis)
    input  wire [NAXES-1:0]     route_ok,        // axis n's three phases drive outputs (out_route mapped = 0b111)
    // pins
    input  wire [NAXES-1:0]     irc_a,
    input  wire [NAXES-1:0]     irc_b,
    input  wire [NAXES-1:0]     irc_idx,
    input  wire [NAXES-1:0]     irc_mark,
    input  wire [3*NAXES-1:0]   hall,
    output wire [3*NAXES-1:0]   pwm_hi,
    output wire [3*NAXES-1:0]   pwm_lo,
    output wire                 adc_sclk,
    output wire                 adc_cs_n,
    input  wire [3*NAXES-1:0]   adc_miso,
    // status for the top (per axis)
    output wire [NAXES-1:0]     period_tick,
    output wire [NAXES-1:0]     control_done,
    output wire [NAXES-1:0]     fault_any,
    output wire [NAXES-1:0]     pwm_trip,       // each axis's trip into its pwm_center (out_route's trip)
    output wire [NAXES-1:0]     bridges_live
);
    localparam integer P = `EMPC_PWM_HALF_PERIOD;
    localparam integer CW = $clog2(P + 1);
    localparam integer STAGGER = (NAXES == 2) ? `EMPC_PWM_STAGGER_2 : (NAXES == 3) ? `EMPC_PWM_STAGGER_3 :
                                 (NAXES == 4) ? `EMPC_PWM_STAGGER_4 : 0;
    localparam integer CAX = $clog2(NAXES);       // axis bits of the shared blocks' {axis, word} addresses
    localparam integer RAW = (N < 2) ? 1 : $clog2(N + 1);
    localparam integer IW = `EMPC_I_W;
    localparam integer AB = `EMPC_ANGLE_BITS;
    localparam integer CUW = `EMPC_ADC_BITS + 1;
    localparam integer AD = `EMPC_ADC_BITS;
    localparam integer PSW = `EMPC_A_ADC_PSUM0_SUM_W;
    localparam integer PCW = `EMPC_A_ADC_PSUM0_COUNT_W;
    // pos_sense's reducer on the low 8 bits of the counts: exact, since irc_decoder moves pos by at most
    // one count per clock and the reducer looks at most 9 clocks apart (rtl/pos_sense.v, JUMP_W)
    localparam integer POS_JUMP_W = 8;

    generate if (NAXES < 2 || NAXES > 4 || CAX != AXB || AD != `EMPC_A_OC_THRESH_W || AD != `EMPC_A_ADC_OFF0_W)
    begin : g_bad_params
        mx_axes_unsupported_parameters u_error ();   // no such module: elaboration stops here (NAXES = 1: mpc_axis)
    end endgenerate

    wire [AXB-1:0] rax = reg_addr[AXB+7:8];          // the CPU's axis
    wire [7:0]     roff = reg_addr[7:0];

    // ---------------- per-axis signals the shared blocks take (axis a at [a*W +: W]) ----------------
    wire [NAXES-1:0]       running, bridges_on;
    wire [8*NAXES-1:0]     ppc;
    wire [NAXES-1:0]       cmd_adc_cal, cmd_coef_swap, cmd_clear_counters;
    wire [18*NAXES-1:0]    kdc_v, kacc_v, id_ref_v, iq_ref_v;
    wire [8*NAXES-1:0]     fw_n_v;          // field-weakening steps (axis_periph's fw_n)
    wire [5*NAXES-1:0]     kacc_shift_v;
    wire [4*NAXES-1:0]     load_shift_v;
    wire [3*NAXES-1:0]     win_v;
    wire [32*NAXES-1:0]    fw_thr_v;
    wire [NAXES-1:0]       iq_big_v;        // |i_q| (the job's, st_iq) >= the axis's IQ_HOLD
    wire [AD*NAXES-1:0]    oc_thr_v, sum_thr_v, off_wdata_v;
    wire [3*NAXES-1:0]     off_we_v;
    wire [4*NAXES-1:0]     seg_addr_v, start_slot_v;
    wire [3*NAXES-1:0]     seg_field_v;
    wire [NAXES-1:0]       seg_we_v, seg_re_v, seg_start_v, ref_sync_d, sync_bit, gov_hold;
    wire [NAXES-1:0]       stat_re_v, cnt_re_v;
    wire [AB*NAXES-1:0]    theta_v;
    wire [32*NAXES-1:0]    pos_v;
    wire [NAXES-1:0]       pos_sample;
    wire [NAXES-1:0]       period_start, adc_trig;
    wire [NAXES-1:0]       ax_core_done;     // the core's done, of the job's axis
    wire [NAXES-1:0]       front_sat_ev, period_ev, gov_ev_ax;

    // ---------------- sensors: current ADC, shared (one frame grid, per-axis windows) ----------------
    wire               adc_busy, adc_fvalid;
    wire [NAXES-1:0]   adc_trig_miss, adc_valid, adc_sat, adc_cal_busy, adc_cal_done, adc_refused;
    wire [NAXES-1:0]   adc_oc, adc_frame_err, adc_stuck, adc_sum_err, adc_frozen;
    wire [8*NAXES-1:0] adc_miss_cnt;
    wire [AD*NAXES-1:0] code0, code1, code2, off0, off1, off2;
    wire [CUW*NAXES-1:0] cur0, cur1, cur2;
    wire [3*NAXES-1:0] oc_ch;
    wire [PSW*NAXES-1:0] psum0, psum1, psum2;
    wire [PCW*NAXES-1:0] pcount;
    adc_spi #(.OFFSET_RESET(`EMPC_A_ADC_OFF0_RESET), .PCNT_W(PCW), .NAXES(NAXES)) u_adc (
        .clk(clk), .rst(rst), .period_start(period_start), .trig(adc_trig), .bridges_on(bridges_on), .busy(adc_busy),
        .trig_miss(adc_trig_miss), .miss_cnt(adc_miss_cnt), .cs_n(adc_cs_n), .sclk(adc_sclk), .miso(adc_miso),
        .fvalid(adc_fvalid), .code0(code0), .code1(code1), .code2(code2), .frame_err(adc_frame_err),
        .oc_thr(oc_thr_v), .oc(adc_oc), .oc_ch(oc_ch), .sum_thr(sum_thr_v), .sum_err(adc_sum_err),
        .stuck(adc_stuck), .frozen(adc_frozen), .valid(adc_valid), .cur0(cur0), .cur1(cur1), .cur2(cur2),
        .sat(adc_sat), .psum0(psum0), .psum1(psum1), .psum2(psum2), .pcount(pcount), .off_we(off_we_v),
        .off_wdata(off_wdata_v), .offset0(off0), .offset1(off1), .offset2(off2), .cal_start(cmd_adc_cal),
        .cal_busy(adc_cal_busy), .cal_done(adc_cal_done), .refused(adc_refused), .refused_clear(cmd_clear_counters));

    // ---------------- reference generator, shared ----------------
    // the CPU's SEG_* / SEG_GOV accesses go to slot {axis, SEG_ADDR of that axis}, the field that axis
    // chose (axis_periph: SEG_GOV = field 7); only the CPU's axis strobes
    reg  [3:0]  seg_slot_c;
    reg  [2:0]  seg_field_c;
    integer     si;
    always @(*) begin
        seg_slot_c = 4'd0; seg_field_c = 3'd0;
        for (si = 0; si < NAXES; si = si + 1) begin
            seg_slot_c = seg_slot_c | (rax == si[AXB-1:0] ? seg_addr_v[4*si +: 4] : 4'd0);
            seg_field_c = seg_field_c | (rax == si[AXB-1:0] ? seg_field_v[3*si +: 3] : 3'd0);
        end
    end
    wire              ref_q;
    wire [CAX+RAW-1:0] ref_age;
    wire [5:0]        ref_bit, sync_idx;
    wire [NAXES-1:0]  ref_advance, ref_ok, ref_busy, task_pos, gov_ev;
    wire [31:0]       seg_rdata;
    ref_gen #(.N(N), .NAXES(NAXES)) u_ref (
        .clk(clk), .rst(rst), .seg_we(|seg_we_v), .seg_re(|seg_re_v), .seg_slot({rax, seg_slot_c}),
        .seg_field(seg_field_c), .seg_wdata(reg_wdata), .seg_rdata(seg_rdata),
        .start(seg_start_v), .start_slot(start_slot_v),
        .sync(ref_sync_d), .sync_idx(sync_idx), .sync_bit(sync_bit), .advance(ref_advance),
        .rd_age(ref_age), .rd_bit(ref_bit), .rd_q(ref_q), .w_ok(ref_ok), .busy(ref_busy),
        .hold(gov_hold), .task_pos(task_pos), .gov_ev(gov_ev));

    // ---------------- sequencer and MPC core, shared ----------------
    wire [AXB-1:0]                  job_axis;
    wire [NAXES-1:0]                job_next;
    reg  [17:0]                     j_kdc, j_kacc, j_idr, j_iq;
    reg  [7:0]                      j_fwn;
    reg  [4:0]                      j_ksh;
    reg  [3:0]                      j_lsh;
    reg  [2:0]                      j_win;
    reg  [31:0]                     j_fw;
    integer                         ji;
    always @(*) begin                // the job axis's registers (AND-OR multiplexers)
        j_kdc = 18'd0; j_kacc = 18'd0; j_idr = 18'd0; j_fwn = 8'd0; j_iq = 18'd0; j_ksh = 5'd0; j_lsh = 4'd0; j_win = 3'd0;
        j_fw = 32'd0;
        for (ji = 0; ji < NAXES; ji = ji + 1) if (job_axis == ji[AXB-1:0]) begin
            j_kdc = j_kdc | kdc_v[18*ji +: 18];
            j_kacc = j_kacc | kacc_v[18*ji +: 18];
            j_idr = j_idr | id_ref_v[18*ji +: 18];
            j_fwn = j_fwn | fw_n_v[8*ji +: 8];
            j_iq = j_iq | iq_ref_v[18*ji +: 18];
            j_ksh = j_ksh | kacc_shift_v[5*ji +: 5];
            j_lsh = j_lsh | load_shift_v[4*ji +: 4];
            j_win = j_win | win_v[3*ji +: 3];
            j_fw = j_fw | fw_thr_v[32*ji +: 32];
        end
    end
    // the job axis's effective d-current reference, formed once from its ID_REF and field-weakening
    // steps (axis_periph's id_eff of that axis, the same expression: sat18(ID_REF - (fw_n << EMPC_FW_SHIFT)))
    wire signed [IW:0]              j_isum = {j_idr[IW-1], j_idr} - ({{(IW+1-8){1'b0}}, j_fwn} << `EMPC_FW_SHIFT);
    wire [17:0]                     j_id = (j_isum[IW] != j_isum[IW-1]) ? {j_isum[IW], {(IW-1){~j_isum[IW]}}} : j_isum[IW-1:0];
    wire [NAXES-1:0]                core_start, ctl_boundary, cmp_load, overrun, seq_front_sat, stat_sweep;
    wire                            core_done, core_busy, core_in_we;
    wire [6+CAX-1:0]                core_in_addr;
    wire signed [`EMPC_SIG_W-1:0]   core_in_wdata;
    wire [2*`EMPC_U_W-1:0]          core_u, core_du, core_u_raw;
    wire [3*`EMPC_SIG_W-1:0]        core_ebar;
    wire signed [`EMPC_OPW-1:0]     core_wn;
    wire [10:0]                     core_flags;
    wire [7:0]                      core_latency;
    wire                            core_ready, core_boot_ok, core_fw_hi, core_fw_lo;
    wire [NAXES-1:0]                core_bank, core_swap_pending, core_img_ok, core_upl_ok, core_swap_refused, core_refused;
    wire [16*NAXES-1:0]             seq_latency;
    wire signed [IW-1:0]            st_id, st_iq;
    wire signed [`EMPC_W_W-1:0]     omega, omega_next;
    wire [AB-1:0]                   theta_trig;
    wire [3*CW-1:0]                 cmp;
    wire                            st_we;
    wire [6+CAX-1:0]                st_addr;
    wire [31:0]                     st_wdata;
    mx_seq #(.N(N), .NAXES(NAXES)) u_seq (
        .clk(clk), .rst(rst), .adc_trig(adc_trig), .period_start(period_start), .pwm_per_control(ppc),
        .run(running), .theta(theta_v), .pos(pos_v), .pos_sample(pos_sample), .adc_valid(adc_valid),
        .cur0(cur0), .cur1(cur1), .cur2(cur2), .job_axis(job_axis), .job_next(job_next),
        .kdc(j_kdc), .kacc(j_kacc), .kacc_shift(j_ksh),
        .load_shift(j_lsh), .win_shift(j_win), .id_ref(j_id), .iq_ref(j_iq), .task_pos(task_pos), .ctl_boundary(ctl_boundary),
        .ref_advance(ref_advance), .ref_ok(ref_ok), .ref_age(ref_age), .ref_bit(ref_bit), .ref_q(ref_q),
        .core_start(core_start), .core_in_we(core_in_we), .core_in_addr(core_in_addr),
        .core_in_wdata(core_in_wdata), .core_done(core_done), .core_u(core_u), .core_ebar(core_ebar),
        .cmp(cmp), .cmp_load(cmp_load), .control_done(control_done), .overrun(overrun),
        .front_sat(seq_front_sat), .latency(seq_latency), .i_d(st_id), .i_q(st_iq), .omega(omega),
        .omega_next(omega_next),
        .theta_trig(theta_trig), .st_we(st_we), .st_addr(st_addr), .st_wdata(st_wdata), .stat_sweep(stat_sweep));

    mpc_core #(.N(N), .NAXES(NAXES), .BOOT_FILE(BOOT_FILE), .RSQRT_FILE(RSQRT_FILE)) u_core (
        .clk(clk), .rst(rst), .start(core_start), .in_we(core_in_we), .in_addr(core_in_addr),
        .in_wdata(core_in_wdata), .busy(core_busy),
        .done(core_done), .u(core_u), .du(core_du), .u_raw(core_u_raw), .ebar(core_ebar), .wn(core_wn),
        .flags(core_flags), .latency(core_latency), .fw_thr(j_fw), .fw_hi(core_fw_hi),
        .fw_lo(core_fw_lo), .aw({st_iq[IW-1], iq_big_v[job_axis]}), .cfg_we(coef_we), .cfg_addr(coef_addr),
        .cfg_wdata(reg_wdata), .cfg_swap(cmd_coef_swap), .swap_at(ctl_boundary), .ready(core_ready), .bank(core_bank),
        .swap_pending(core_swap_pending), .boot_ok(core_boot_ok), .img_ok(core_img_ok), .upl_ok(core_upl_ok),
        .swap_refused(core_swap_refused), .refused(core_refused), .task_pos(task_pos), .pwm_per_control(ppc));

    // ---------------- status words and counters, shared (one block RAM {axis, word}) ----------------
    wire [31:0]      s_q;
    wire [NAXES-1:0] status_busy;
    axis_status #(.NAXES(NAXES)) u_status (
        .clk(clk), .rst(rst), .reg_rd(reg_rd), .reg_addr(reg_addr), .cnt_re(|cnt_re_v), .stat_re(|stat_re_v),
        .rdata(s_q), .cnt_clear(cmd_clear_counters), .core_done(ax_core_done), .core_flags({NAXES{core_flags}}),
        .front_sat(front_sat_ev), .overrun(overrun), .period(period_ev), .gov(gov_ev_ax),
        .st_we(st_we), .st_addr(st_addr), .st_wdata(st_wdata), .sweep(stat_sweep), .busy(status_busy));

    // ---------------- per axis: sensors, glue, faults, PWM, registers ----------------
    localparam integer VW = `EMPC_A_RD_VALS_W;
    wire [VW*NAXES-1:0] rd_vals_v;       // the readable values of every axis (axis_regs.rd_vals)
    localparam integer NSH = `EMPC_A_SH_N;
    wire [NSH*NAXES-1:0] sh_we_v;        // accepted writes of the shadowed registers (axis_regs.sh_we)
    genvar n;
    generate for (n = 0; n < NAXES; n = n + 1) begin : g_ax
        localparam integer PHASE = n * STAGGER;
        wire job_is_n = (job_axis == n[AXB-1:0]);
        wire sel = (rax == n[AXB-1:0]);
        assign ax_core_done[n] = core_done && job_is_n;

        // this axis's speed for the reference sync: the core's omega while its job runs, held after;
        // loaded with omega's next value in the clock before the job axis is n (job_next[n]: n is the
        // job axis in the next clock), so omega_n equals (job_is_n ? omega : omega held from the
        // last clock with job_is_n) every clock without a multiplexer per axis
        reg  [31:0] omega_n;
        always @(posedge clk) if (rst) omega_n <= 32'd0; else if (job_next[n]) omega_n <= omega_next;

        // ---- the axis (rtl/axis_periph.v, as mpc_axis's): sensors, registers, glue, faults, PWM ----
        /* verilator lint_off PINCONNECTEMPTY */    // pwm_sync_out: the carriers are phased by PHASE
        axis_periph #(.HALL_DEBOUNCE(HALL_DEBOUNCE), .ENC_FILTER(ENC_FILTER), .COMPLEMENTARY(COMPLEMENTARY),
                      .PWM_HALF_PERIOD(P), .PHASE(PHASE), .POS_JUMP_W(POS_JUMP_W)) u_per (
            .clk(clk), .rst(rst), .reg_wr(reg_wr && sel), .reg_rd(reg_rd && sel), .reg_addr(roff),
            .reg_wdata(reg_wdata), .reg_rdata(), .rd_vals(rd_vals_v[VW*n +: VW]),
            .sh_we(sh_we_v[NSH*n +: NSH]), .watchdog_expired(watchdog_expired),
            .g_wr_refused(g_wr_refused), .ext_fault(ext_fault), .route_ok(route_ok[n]), .pwm_sync_in(1'b0), .pwm_sync_out(),
            .irc_a(irc_a[n]), .irc_b(irc_b[n]), .irc_idx(irc_idx[n]), .irc_mark(irc_mark[n]), .hall(hall[3*n +: 3]),
            .pwm_hi(pwm_hi[3*n +: 3]), .pwm_lo(pwm_lo[3*n +: 3]), .period_start(period_start[n]),
            .adc_trig(adc_trig[n]), .bridges_on(bridges_on[n]), .running(running[n]),
            .bridges_live(bridges_live[n]), .fault_any(fault_any[n]), .pwm_trip(pwm_trip[n]),
            .cmd_adc_cal(cmd_adc_cal[n]), .cmd_clear_counters(cmd_clear_counters[n]), .oc_thresh(oc_thr_v[AD*n +: AD]),
            .adc_sum_thresh(sum_thr_v[AD*n +: AD]), .adc_off_we(off_we_v[3*n +: 3]),
            .adc_off_wdata(off_wdata_v[AD*n +: AD]),
            .adc_oc(adc_oc[n]), .adc_frame_err(adc_frame_err[n]), .adc_stuck(adc_stuck[n]),
            .adc_sum_err(adc_sum_err[n]), .adc_frozen(adc_frozen[n]), .adc_sat(adc_sat[n]),
            .adc_cal_busy(adc_cal_busy[n]), .adc_cal_done(adc_cal_done[n]), .adc_refused(adc_refused[n]),
            .adc_miss_cnt(adc_miss_cnt[8*n +: 8]), .code0(code0[AD*n +: AD]), .code1(code1[AD*n +: AD]),
            .code2(code2[AD*n +: AD]), .off0(off0[AD*n +: AD]), .off1(off1[AD*n +: AD]), .off2(off2[AD*n +: AD]),
            .psum0(psum0[PSW*n +: PSW]), .psum1(psum1[PSW*n +: PSW]), .psum2(psum2[PSW*n +: PSW]),
            .pcount(pcount[PCW*n +: PCW]),
            .seg_we(seg_we_v[n]), .seg_re(seg_re_v[n]), .seg_slot(seg_addr_v[4*n +: 4]),
            .seg_field(seg_field_v[3*n +: 3]), .seg_start(seg_start_v[n]), .seg_start_slot(start_slot_v[4*n +: 4]),
            .seg_rdata(seg_rdata), .ref_sync(ref_sync_d[n]), .sync_idx(sync_idx), .sync_bit(sync_bit[n]),
            .task_pos(task_pos[n]), .gov_ev(gov_ev[n]), .gov_hold(gov_hold[n]),
            .ctrl_pwm_per_control(ppc[8*n +: 8]), .theta(theta_v[AB*n +: AB]), .pos(pos_v[32*n +: 32]),
            .pos_sample(pos_sample[n]), .kdc(kdc_v[18*n +: 18]), .kacc(kacc_v[18*n +: 18]),
            .kacc_shift(kacc_shift_v[5*n +: 5]), .kacc_load_shift(load_shift_v[4*n +: 4]), .kacc_win(win_v[3*n +: 3]),
            .id_eff(), .id_ref_q(id_ref_v[18*n +: 18]), .fw_step(fw_n_v[8*n +: 8]), .iq_ref(iq_ref_v[18*n +: 18]), .cmp(cmp), .cmp_load(cmp_load[n]),
            .overrun(overrun[n]), .seq_front_sat(seq_front_sat[n]), .control_done(control_done[n]),
            .seq_latency(seq_latency[16*n +: 16]), .st_iq(st_iq), .omega(omega_n),
            .fw_thr(fw_thr_v[32*n +: 32]), .iq_big(iq_big_v[n]), .cmd_coef_swap(cmd_coef_swap[n]),
            .core_done(ax_core_done[n]), .core_limit(core_flags[`EMPC_FLAG_LIMIT]), .core_fw_hi(core_fw_hi),
            .core_fw_lo(core_fw_lo), .core_ready(core_ready), .core_img_ok(core_img_ok[n]), .core_bank(core_bank[n]),
            .core_swap_pending(core_swap_pending[n]), .core_upl_ok(core_upl_ok[n]),
            .core_swap_refused(core_swap_refused[n]), .core_refused(core_refused[n]),
            .stat_re(stat_re_v[n]), .cnt_re(cnt_re_v[n]), .st_front_sat(front_sat_ev[n]), .st_period(period_ev[n]),
            .st_gov(gov_ev_ax[n]), .smem_rdata(s_q));
        /* verilator lint_on PINCONNECTEMPTY */
        assign period_tick[n] = period_start[n];
    end endgenerate

    // ---------------- register read path, shared (generated: rtl/axis_rd.v) ----------------
    // the CPU reads one axis at a time: one set of gated copies takes each live value from axis rax, the
    // stored registers come from a write-through block RAM {axis, word} written at the axes' sh_we
    // (the axes' own axis_regs copies are left open and dropped); the windows' read data ORed there
    axis_rd #(.NAXES(NAXES)) u_rd (
        .clk(clk), .rst(rst), .reg_rd(reg_rd), .rd_axis(rax), .reg_addr(roff), .rd_vals(rd_vals_v),
        .reg_wdata(reg_wdata), .sh_we(sh_we_v),
        .seg_rdata(seg_rdata), .smem_rdata(s_q), .reg_rdata(reg_rdata));

    wire unused = &{1'b0, adc_busy, adc_fvalid, adc_trig_miss, oc_ch, ref_busy, core_busy, core_du, core_u_raw,
                    core_wn, core_latency, core_boot_ok, st_id, st_iq[3:0], theta_trig, status_busy,
                    omega};
endmodule
`default_nettype wire
