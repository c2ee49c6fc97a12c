// adc_spi_tb: simulation-only wrapper for tb/test_adc_spi.py: adc_spi (master)
// wired pin-to-pin to adc_spi_slave (three ADC models).  All master inputs are
// brought out; the master's outputs are concatenated into `mon` (one read per
// clock in the test; field order in tb/test_adc_spi.py MON_FIELDS, LSB first).
// The slave's code inputs, lead-bit pattern and monitors are reachable as
// s_code0..2 / s_lead / u_slave.*.
`default_nettype none
`timescale 1ns / 1ps
module adc_spi_tb #(
    parameter integer ADC_BITS       = 12,
    parameter integer FRAME_BITS     = 16,
    parameter integer LEAD_ZEROS     = 4,
    parameter integer SCLK_DIV       = 2,
    parameter integer SAMPLE_DELAY   = 5,
    parameter integer CS_QUIET       = 5,
    parameter integer HALF_PERIOD    = 400,
    parameter integer AVG_LOG2       = 2,
    parameter integer FRAME_PERIOD   = 0,
    parameter integer CAL_LOG2       = 10,
    parameter integer CUR_W          = ADC_BITS + 1,
    parameter integer MISS_W         = 8,
    parameter integer OFFSET_RESET   = 2048,
    parameter integer PCNT_W         = 7,
    parameter integer SUM_PERSIST    = 4,
    parameter integer STUCK_PERSIST  = 4,
    parameter integer FROZEN_PERIODS = 4,
    parameter integer T_HOLD_PS      = 3000,
    parameter integer T_OUT_PS       = 15000,
    parameter integer MON_W = 18 + MISS_W + 6 * ADC_BITS + 3 * CUR_W + 3 * (ADC_BITS + 1 + PCNT_W) + PCNT_W
) (
    input  wire                     clk,
    input  wire                     rst,
    input  wire                     period_start,
    input  wire                     trig,
    input  wire                     bridges_on,
    input  wire [ADC_BITS-1:0]      oc_thr,
    input  wire [ADC_BITS-1:0]      sum_thr,
    input  wire [2:0]               off_we,
    input  wire [ADC_BITS-1:0]      off_wdata,
    input  wire                     cal_start,
    input  wire                     refused_clear,
    output wire [MON_W-1:0]         mon,
    output wire                     cs_n,
    output wire                     sclk,
    output wire                     oc,
    output wire [2:0]               miso,
    // slave side
    input  wire [ADC_BITS-1:0]      s_code0,
    input  wire [ADC_BITS-1:0]      s_code1,
    input  wire [ADC_BITS-1:0]      s_code2,
    input  wire [3*LEAD_ZEROS-1:0]  s_lead
);
    localparam integer PSW = ADC_BITS + 1 + PCNT_W;
    wire                  busy, trig_miss, fvalid, frame_err, sum_err, stuck, frozen, valid, sat;
    wire                  cal_busy, cal_done, refused;
    wire [MISS_W-1:0]     miss_cnt;
    wire [ADC_BITS-1:0]   code0, code1, code2, offset0, offset1, offset2;
    wire [2:0]            oc_ch;
    wire [CUR_W-1:0]      cur0, cur1, cur2;
    wire [PSW-1:0]        psum0, psum1, psum2;
    wire [PCNT_W-1:0]     pcount;

    adc_spi #(
        .ADC_BITS(ADC_BITS), .FRAME_BITS(FRAME_BITS), .LEAD_ZEROS(LEAD_ZEROS), .SCLK_DIV(SCLK_DIV),
        .SAMPLE_DELAY(SAMPLE_DELAY), .CS_QUIET(CS_QUIET), .HALF_PERIOD(HALF_PERIOD), .AVG_LOG2(AVG_LOG2),
        .FRAME_PERIOD(FRAME_PERIOD), .CAL_LOG2(CAL_LOG2), .CUR_W(CUR_W), .MISS_W(MISS_W),
        .OFFSET_RESET(OFFSET_RESET), .PCNT_W(PCNT_W), .SUM_PERSIST(SUM_PERSIST), .STUCK_PERSIST(STUCK_PERSIST),
        .FROZEN_PERIODS(FROZEN_PERIODS)
    ) u_dut (
        .clk(clk), .rst(rst), .period_start(period_start), .trig(trig), .bridges_on(bridges_on), .busy(busy),
        .trig_miss(trig_miss), .miss_cnt(miss_cnt), .cs_n(cs_n), .sclk(sclk), .miso(miso),
        .fvalid(fvalid), .code0(code0), .code1(code1), .code2(code2), .frame_err(frame_err),
        .oc_thr(oc_thr), .oc(oc), .oc_ch(oc_ch), .sum_thr(sum_thr), .sum_err(sum_err), .stuck(stuck),
        .frozen(frozen), .valid(valid), .cur0(cur0), .cur1(cur1), .cur2(cur2), .sat(sat),
        .psum0(psum0), .psum1(psum1), .psum2(psum2), .pcount(pcount),
        .off_we(off_we), .off_wdata(off_wdata), .offset0(offset0), .offset1(offset1), .offset2(offset2),
        .cal_start(cal_start), .cal_busy(cal_busy), .cal_done(cal_done), .refused(refused),
        .refused_clear(refused_clear)
    );

    assign mon = {sclk, refused, cal_done, cal_busy, offset2, offset1, offset0, pcount, psum2, psum1, psum0,
                  sat, cur2, cur1, cur0, valid, frozen, stuck, sum_err, oc_ch, oc, frame_err,
                  code2, code1, code0, fvalid, miss_cnt, trig_miss, busy, cs_n};

    adc_spi_slave #(
        .ADC_BITS(ADC_BITS), .FRAME_BITS(FRAME_BITS), .LEAD_ZEROS(LEAD_ZEROS),
        .T_HOLD_PS(T_HOLD_PS), .T_OUT_PS(T_OUT_PS)
    ) u_slave (
        .sclk(sclk), .cs_n(cs_n), .code0(s_code0), .code1(s_code1), .code2(s_code2),
        .lead(s_lead), .miso(miso)
    );
endmodule
`default_nettype wire
