// cosim_obs: the per-PWM-period observation registers of one axis in the RTL-in-the-loop co-simulations
// (tb/hdl/cosim_top.v: one axis; tb/hdl/cosim_axis.v: one per axis of tb/hdl/cosim4_top.v).
//
// Python wakes once per PWM period, at period_start; these registers hold what it used to wait for
// inside the period: the compare values at the last cmp_load, the clocks from the last adc_trig and
// from the last ADC valid to that load (tb/test_closed_loop.py adds the fixed clocks from the window's
// last bit to valid), `running` at the last trigger, how many triggers and loads the period had; a
// sticky monitor (unsafe) flags a bridge enable or PWM output high in a clock after one with trip; and
// the MPC core's input words of this axis as the sequencer last wrote them (word a at
// [a*SIG_W +: SIG_W]: one VPI read per control period).
// Reset: synchronous, rst_n low.  Latency: every output registered one clock after its event.
`default_nettype none
`include "empc_formats.vh"
module cosim_obs #(
    parameter integer IN_AW = $clog2(`EMPC_IN_WORDS)
) (
    input  wire        clk,
    input  wire        rst_n,
    input  wire        period_start,
    input  wire        adc_trig,
    input  wire        adc_valid,
    input  wire        cmp_load,
    input  wire [35:0] cmp,
    input  wire        running,
    input  wire        trip,
    input  wire [5:0]  pins,            // the axis's bridge pins {pwm_en, pwm_out}
    input  wire        in_we,           // a core input word of this axis
    input  wire [IN_AW-1:0] in_addr,
    input  wire [`EMPC_SIG_W-1:0] in_wdata,
    output reg  [35:0] cmp_q,           // compare values at the last cmp_load
    output reg  [15:0] lat_q,           // clocks from the last adc_trig to that cmp_load
    output reg  [15:0] lat_valid_q,     // clocks from the last ADC valid to that cmp_load
    output reg         run_trig,        // `running` at the last adc_trig
    output reg  [3:0]  n_trig,          // adc_trig pulses since the last period start
    output reg  [3:0]  n_load,          // cmp_load pulses since the last period start
    output reg         unsafe,          // sticky: a bridge pin high in a clock after one with trip
    output reg  [`EMPC_IN_WORDS*`EMPC_SIG_W-1:0] in_words
);
    reg [15:0] lat_cnt, valid_cnt;
    reg        tripped;
    always @(posedge clk) begin
        if (!rst_n) begin
            cmp_q <= 36'd0;
            lat_q <= 16'd0;
            run_trig <= 1'b0;
            n_trig <= 4'd0;
            n_load <= 4'd0;
            unsafe <= 1'b0;
            lat_cnt <= 16'd0;
            tripped <= 1'b0;
            lat_valid_q <= 16'd0;
            valid_cnt <= 16'd0;
        end else begin
            lat_cnt <= adc_trig ? 16'd1 : (&lat_cnt ? lat_cnt : lat_cnt + 16'd1);
            if (adc_trig) run_trig <= running;
            valid_cnt <= adc_valid ? 16'd1 : (&valid_cnt ? valid_cnt : valid_cnt + 16'd1);
            if (cmp_load) begin
                cmp_q <= cmp;
                lat_q <= lat_cnt;
                lat_valid_q <= valid_cnt;
            end
            n_trig <= (period_start ? 4'd0 : n_trig) + {3'd0, adc_trig};
            n_load <= (period_start ? 4'd0 : n_load) + {3'd0, cmp_load};
            tripped <= trip;
            if (tripped && |pins) unsafe <= 1'b1;
        end
    end
    always @(posedge clk)
        if (in_we) in_words[in_addr*`EMPC_SIG_W +: `EMPC_SIG_W] <= in_wdata;
endmodule
`default_nettype wire
