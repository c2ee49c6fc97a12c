// mx_seq_axes_tb: simulation wrapper for tb/test_mx_seq.py's several-axes test (NAXES = 2..4): mx_seq,
// ref_gen and mpc_core, all with NAXES, and the PWM timing of every axis generated here, so that Python
// wakes up once per PWM period of each axis (not every clock):
//   carriers: after `go`, axis a's period starts PHASE_a = a * STAGGER clocks later and repeats every
//     2 * EMPC_PWM_HALF_PERIOD clocks (pwm_center's PHASE, docs/four_axes.md 3.1): period_start at its
//     count 0, adc_trig at the centre (count P), adc_valid T_VALID clocks after the trigger;
//   per axis, registered at its cmp_load: the compare values (cmp_q), the clock (tload), a count
//     (nload); counts of front_sat pulses, of status writes and the last status word per axis (from
//     st_addr's axis bits), of overrun pulses, and of core input writes whose axis bits are not the
//     axis of the core's next start (bad_in: must stay 0).
// The sync value of each axis is an input (sync_val): ref_gen's sync_bit[a] = its bit sync_idx.
`default_nettype none
`include "empc_formats.vh"
module mx_seq_axes_tb #(
    parameter integer N = 4,
    parameter integer NAXES = 2,
    parameter integer STAGGER = 2516,
    parameter integer T_VALID = 71,
    parameter [`EMPC_IMG_CFG_PERIOD_BITS-1:0] PPC_IMG = `EMPC_PWM_PER_CONTROL
) (
    input  wire clk, input wire rst, input wire go,
    input  wire [8*NAXES-1:0] ppc, input wire [NAXES-1:0] run, input wire [NAXES-1:0] hold,
    input  wire [16*NAXES-1:0] theta, input wire [32*NAXES-1:0] pos,
    input  wire [13*NAXES-1:0] cur0, input wire [13*NAXES-1:0] cur1, input wire [13*NAXES-1:0] cur2,
    input  wire [18*NAXES-1:0] kdc, input wire [18*NAXES-1:0] kacc, input wire [5*NAXES-1:0] kacc_shift,
    input  wire [4*NAXES-1:0] load_shift, input wire [3*NAXES-1:0] win_shift, input wire [18*NAXES-1:0] id_ref, input wire [18*NAXES-1:0] iq_ref,
    input  wire seg_we, input wire [$clog2(NAXES)+3:0] seg_slot, input wire [2:0] seg_field,
    input  wire [31:0] seg_wdata,
    input  wire [NAXES-1:0] start, input wire [4*NAXES-1:0] start_slot, input wire [NAXES-1:0] sync,
    input  wire [64*NAXES-1:0] sync_val,
    input  wire cfg_we, input wire [9+$clog2(NAXES):0] cfg_addr, input wire [31:0] cfg_wdata,
    input  wire [NAXES-1:0] cfg_swap, input wire [NAXES-1:0] swap_at,
    output wire [NAXES-1:0] task_pos, output wire core_ready, output wire [NAXES-1:0] swap_pending,
    output wire [NAXES-1:0] ref_busy,
    output reg  [31:0] tick,
    output reg  [36*NAXES-1:0] cmp_q, output reg [32*NAXES-1:0] tload, output reg [16*NAXES-1:0] nload,
    output wire [16*NAXES-1:0] latency,
    output reg  [16*NAXES-1:0] nfs, output reg [16*NAXES-1:0] nst, output reg [32*NAXES-1:0] st_last,
    output reg  [16*NAXES-1:0] novr, output reg [15:0] bad_in
);
    localparam integer AXP = $clog2(NAXES);
    localparam integer AW = (N < 2) ? 1 : $clog2(N + 1);
    localparam integer P = `EMPC_PWM_HALF_PERIOD;
    localparam [13:0] C_TRIG = P, C_VALID = P + T_VALID, C_LAST = 2 * P - 1;
    // ---- carriers ----
    reg  [NAXES-1:0] on;
    reg  [13:0] cnt [0:NAXES-1];
    wire [NAXES-1:0] period_start, adc_trig, adc_valid;
    genvar a;
    generate for (a = 0; a < NAXES; a = a + 1) begin : g_car
        always @(posedge clk) begin
            if (rst || !go) begin
                on[a] <= 1'b0;
                cnt[a] <= 14'd0;
            end else if (!on[a]) begin
                if (tick == a * STAGGER) on[a] <= 1'b1;
            end else
                cnt[a] <= (cnt[a] == C_LAST) ? 14'd0 : cnt[a] + 14'd1;
        end
        assign period_start[a] = on[a] && cnt[a] == 14'd0;
        assign adc_trig[a] = on[a] && cnt[a] == C_TRIG;
        assign adc_valid[a] = on[a] && cnt[a] == C_VALID;
    end endgenerate
    always @(posedge clk) tick <= (rst || !go) ? 32'd0 : tick + 32'd1;

    // ---- the blocks ----
    wire [NAXES-1:0] ref_advance, ref_ok, ctl_boundary, pos_sample, core_start, cmp_load, control_done, overrun,
                     front_sat, stat_sweep, sync_bit;
    wire ref_q; wire [AXP+AW-1:0] ref_age; wire [5:0] ref_bit, sync_idx;
    wire core_done, core_in_we; wire [5+AXP:0] core_in_addr; wire signed [`EMPC_SIG_W-1:0] core_in_wdata;
    wire [47:0] core_u, core_du, core_u_raw; wire [3*`EMPC_SIG_W-1:0] core_ebar; wire [17:0] core_wn;
    wire [10:0] core_flags; wire [7:0] core_latency; wire core_busy, core_boot_ok;
    wire [NAXES-1:0] core_bank;
    wire [17:0] i_d, i_q; wire [31:0] omega; wire [15:0] theta_trig; wire [31:0] seg_rdata;
    wire [AXP-1:0] job_axis;         // the register block's read address (here: the vectors' element)
    wire st_we; wire [5+AXP:0] st_addr; wire [31:0] st_wdata; wire [35:0] cmp;
    generate for (a = 0; a < NAXES; a = a + 1) begin : g_sync
        assign sync_bit[a] = sync_val[64 * a + sync_idx];
    end endgenerate
    ref_gen #(.N(N), .NAXES(NAXES)) u_ref (.clk(clk), .rst(rst), .seg_we(seg_we), .seg_re(1'b0),
        .seg_slot(seg_slot), .seg_field(seg_field), .seg_wdata(seg_wdata), .seg_rdata(seg_rdata), .start(start),
        .start_slot(start_slot), .sync(sync), .sync_idx(sync_idx), .sync_bit(sync_bit), .advance(ref_advance),
        .rd_age(ref_age), .rd_bit(ref_bit), .rd_q(ref_q), .w_ok(ref_ok), .busy(ref_busy), .hold(hold),
        .task_pos(task_pos), .gov_ev());
    mx_seq #(.N(N), .NAXES(NAXES)) u_seq (.clk(clk), .rst(rst), .adc_trig(adc_trig), .period_start(period_start),
        .pwm_per_control(ppc), .run(run), .theta(theta), .pos(pos), .pos_sample(pos_sample), .adc_valid(adc_valid),
        .cur0(cur0), .cur1(cur1), .cur2(cur2), .job_axis(job_axis), .job_next(), .kdc(kdc[18*job_axis +: 18]),
        .kacc(kacc[18*job_axis +: 18]), .kacc_shift(kacc_shift[5*job_axis +: 5]),
        .load_shift(load_shift[4*job_axis +: 4]), .win_shift(win_shift[3*job_axis +: 3]), .id_ref(id_ref[18*job_axis +: 18]),
        .iq_ref(iq_ref[18*job_axis +: 18]), .task_pos(task_pos),
        .ctl_boundary(ctl_boundary), .ref_advance(ref_advance), .ref_ok(ref_ok), .ref_age(ref_age),
        .ref_bit(ref_bit), .ref_q(ref_q), .core_start(core_start), .core_in_we(core_in_we),
        .core_in_addr(core_in_addr), .core_in_wdata(core_in_wdata), .core_done(core_done), .core_u(core_u),
        .core_ebar(core_ebar), .cmp(cmp), .cmp_load(cmp_load), .control_done(control_done), .overrun(overrun),
        .front_sat(front_sat), .latency(latency), .i_d(i_d), .i_q(i_q), .omega(omega), .omega_next(),
        .theta_trig(theta_trig), .st_we(st_we), .st_addr(st_addr), .st_wdata(st_wdata), .stat_sweep(stat_sweep));
    mpc_core #(.N(N), .NAXES(NAXES)) u_core (.clk(clk), .rst(rst), .start(core_start), .in_we(core_in_we),
        .in_addr(core_in_addr), .in_wdata(core_in_wdata), .busy(core_busy), .done(core_done), .u(core_u),
        .du(core_du), .u_raw(core_u_raw), .ebar(core_ebar), .wn(core_wn), .flags(core_flags),
        .latency(core_latency), .fw_thr(32'd0), .fw_hi(), .fw_lo(), .aw(2'b00), .cfg_we(cfg_we), .cfg_addr(cfg_addr),
        .cfg_wdata(cfg_wdata), .cfg_swap(cfg_swap), .swap_at(ctl_boundary | swap_at), .ready(core_ready),
        .bank(core_bank), .swap_pending(swap_pending), .boot_ok(core_boot_ok), .img_ok(), .upl_ok(),
        .swap_refused(), .refused(), .task_pos(task_pos),
        .pwm_per_control({NAXES{PPC_IMG}}));   // the images' control period (the period rule: tb/test_mpc_core.py)

    // ---- monitors ----
    reg  [AXP-1:0] in_ax;           // the axis bits of the last core input write
    reg            in_seen;
    integer k;
    always @(posedge clk) begin
        if (rst) begin
            nload <= 0; nfs <= 0; nst <= 0; novr <= 0; bad_in <= 16'd0; in_seen <= 1'b0;
            cmp_q <= 0; tload <= 0; st_last <= 0; in_ax <= {AXP{1'b0}};
        end else begin
            for (k = 0; k < NAXES; k = k + 1) begin
                if (cmp_load[k]) begin
                    cmp_q[36*k +: 36] <= cmp;
                    tload[32*k +: 32] <= tick;
                    nload[16*k +: 16] <= nload[16*k +: 16] + 16'd1;
                end
                if (front_sat[k]) nfs[16*k +: 16] <= nfs[16*k +: 16] + 16'd1;
                if (overrun[k]) novr[16*k +: 16] <= novr[16*k +: 16] + 16'd1;
                if (st_we && st_addr[5+AXP:6] == k[AXP-1:0]) begin
                    nst[16*k +: 16] <= nst[16*k +: 16] + 16'd1;
                    st_last[32*k +: 32] <= st_wdata;
                end
            end
            if (core_in_we) begin
                in_ax <= core_in_addr[5+AXP:6];
                in_seen <= 1'b1;
            end
            // the core's start must be of the axis whose input words were written last
            if (|core_start && in_seen && !core_start[in_ax]) bad_in <= bad_in + 16'd1;
        end
    end
    wire unused = &{1'b0, i_d, i_q, omega, theta_trig, seg_rdata, core_du, core_u_raw, core_wn, core_flags,
                    core_latency, core_busy, core_bank, core_boot_ok, pos_sample, control_done, stat_sweep};
endmodule
`default_nettype wire
