// mx_seq_tb: simulation wrapper for tb/test_mx_seq.py: mx_seq with the blocks it talks to (ref_gen
// with its governor, mpc_core, axis_status with no events; field weakening and the governor's hold
// live in mpc_axis: hold is an input here), driven directly by the test so that periods, registers
// and reference programs can be randomised far beyond what the closed loop produces.
`default_nettype none
`include "empc_formats.vh"
module mx_seq_tb #(
    parameter integer N = 4,
    parameter [`EMPC_IMG_CFG_PERIOD_BITS-1:0] PPC_IMG = `EMPC_PWM_PER_CONTROL
) (
    input  wire clk, input wire rst,
    input  wire adc_trig, input wire period_start, input wire [7:0] ppc, input wire run,
    input  wire [15:0] theta, input wire [31:0] pos, input wire adc_valid,
    input  wire signed [12:0] cur0, input wire signed [12:0] cur1, input wire signed [12:0] cur2,
    input  wire [17:0] kdc, input wire signed [17:0] kacc, input wire [4:0] kacc_shift, input wire [3:0] load_shift, input wire [2:0] win_shift,
    input  wire hold,
    input  wire signed [17:0] id_ref, input wire signed [17:0] iq_ref,
    input  wire seg_we, input wire [3:0] seg_slot, input wire [2:0] seg_field, input wire [31:0] seg_wdata,
    input  wire start, input wire [3:0] start_slot, input wire sync, input wire sync_bit, output wire [5:0] sync_idx,
    input  wire cfg_we, input wire [9:0] cfg_addr, input wire [31:0] cfg_wdata, input wire cfg_swap,
    input  wire swap_at,        // extra control-period boundary for a swap before the first period
    input  wire force_pos,      // position task without an image (N != 4: the build refuses N = 4's images)
    output wire cmp_load, output wire [35:0] cmp, output wire ref_busy, output wire [15:0] latency,
    output wire front_sat, output wire task_pos, output wire core_ready, output wire swap_pending,
    output wire st_we, output wire [5:0] st_addr, output wire [31:0] st_wdata, output wire control_done,
    output wire stat_sweep, output wire overrun
);
    localparam integer AW = (N < 2) ? 1 : $clog2(N + 1);
    wire ref_advance, ref_ok, ref_q; wire [AW-1:0] ref_age; wire [5:0] ref_bit;
    wire core_start, core_done, core_in_we; wire [5:0] core_in_addr; wire signed [`EMPC_SIG_W-1:0] core_in_wdata;
    wire [47:0] core_u, core_du, core_u_raw; wire [3*`EMPC_SIG_W-1:0] core_ebar; wire [17:0] core_wn;
    wire [10:0] core_flags; wire [7:0] core_latency; wire core_busy, core_bank, core_boot_ok, core_task_pos;
    wire pos_sample, ctl_boundary; wire [17:0] i_d, i_q; wire [31:0] omega; wire [15:0] theta_trig; wire [31:0] seg_rdata;
    ref_gen #(.N(N)) u_ref (.clk(clk), .rst(rst), .seg_we(seg_we), .seg_re(1'b0), .seg_slot(seg_slot),
        .seg_field(seg_field), .seg_wdata(seg_wdata), .seg_rdata(seg_rdata), .start(start), .start_slot(start_slot),
        .sync(sync), .sync_idx(sync_idx), .sync_bit(sync_bit), .advance(ref_advance), .rd_age(ref_age),
        .rd_bit(ref_bit), .rd_q(ref_q), .w_ok(ref_ok), .busy(ref_busy), .hold(hold), .task_pos(task_pos),
        .gov_ev());
    mx_seq #(.N(N)) u_seq (.clk(clk), .rst(rst), .adc_trig(adc_trig), .period_start(period_start),
        .pwm_per_control(ppc), .run(run), .theta(theta), .pos(pos), .pos_sample(pos_sample), .adc_valid(adc_valid),
        .cur0(cur0), .cur1(cur1), .cur2(cur2), .job_axis(), .job_next(),
        .kdc(kdc), .kacc(kacc), .kacc_shift(kacc_shift),
        .load_shift(load_shift), .win_shift(win_shift), .id_ref(id_ref), .iq_ref(iq_ref), .task_pos(task_pos), .ctl_boundary(ctl_boundary), .ref_advance(ref_advance),
        .ref_ok(ref_ok), .ref_age(ref_age), .ref_bit(ref_bit), .ref_q(ref_q), .core_start(core_start),
        .core_in_we(core_in_we), .core_in_addr(core_in_addr), .core_in_wdata(core_in_wdata), .core_done(core_done),
        .core_u(core_u), .core_ebar(core_ebar), .cmp(cmp), .cmp_load(cmp_load), .control_done(control_done),
        .overrun(overrun), .front_sat(front_sat), .latency(latency), .i_d(i_d), .i_q(i_q), .omega(omega), .omega_next(),
        .theta_trig(theta_trig), .st_we(st_we), .st_addr(st_addr), .st_wdata(st_wdata), .stat_sweep(stat_sweep));
    mpc_core #(.N(N)) u_core (.clk(clk), .rst(rst), .start(core_start), .in_we(core_in_we), .in_addr(core_in_addr),
        .in_wdata(core_in_wdata), .busy(core_busy), .done(core_done), .u(core_u), .du(core_du), .u_raw(core_u_raw),
        .ebar(core_ebar), .wn(core_wn), .flags(core_flags), .latency(core_latency), .fw_thr(32'd0), .aw(2'b00), .fw_hi(),
        .fw_lo(), .cfg_we(cfg_we),
        .cfg_addr(cfg_addr), .cfg_wdata(cfg_wdata), .cfg_swap(cfg_swap), .swap_at(ctl_boundary | swap_at),
        .ready(core_ready), .bank(core_bank), .swap_pending(swap_pending), .boot_ok(core_boot_ok), .img_ok(),
        .upl_ok(), .swap_refused(), .refused(), .task_pos(core_task_pos),
        .pwm_per_control(PPC_IMG));     // the images' control period (the period rule: tb/test_mpc_core.py)
    assign task_pos = core_task_pos | force_pos;
    wire unused = &{1'b0, i_d, i_q, omega, theta_trig, seg_rdata, core_du, core_u_raw, core_wn,
                    core_flags, core_latency, core_busy, core_bank, core_boot_ok, pos_sample};
endmodule
`default_nettype wire
