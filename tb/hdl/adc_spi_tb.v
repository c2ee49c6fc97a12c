// adc_spi_tb: simulation-only wrapper for tb/test_adc_spi.py: adc_spi (master)
// wired pin-to-pin to adc_spi_slave (three ADC models).  All master ports are
// brought out unchanged; the slave's code inputs, lead-bit pattern and
// monitors are reachable as s_code0..2 / s_lead / u_slave.*.
`default_nettype none
`timescale 1ns / 1ps
module adc_spi_tb #(
    parameter integer ADC_BITS     = 12,
    parameter integer FRAME_BITS   = 16,
    parameter integer LEAD_ZEROS   = 4,
    parameter integer SCLK_DIV     = 2,
    parameter integer SAMPLE_DELAY = 5,
    parameter integer CS_QUIET     = 5,
    parameter integer CAL_LOG2     = 6,
    parameter integer CUR_W        = ADC_BITS + 1,
    parameter integer MISS_W       = 8,
    parameter integer OFFSET_RESET = 2048,
    parameter integer T_HOLD_PS    = 3000,
    parameter integer T_OUT_PS     = 15000
) (
    input  wire                     clk,
    input  wire                     rst,
    input  wire                     trig,
    output wire                     busy,
    output wire                     trig_miss,
    output wire [MISS_W-1:0]        miss_cnt,
    output wire                     cs_n,
    output wire                     sclk,
    output wire [2:0]               miso,
    output wire                     valid,
    output wire [ADC_BITS-1:0]      code0,
    output wire [ADC_BITS-1:0]      code1,
    output wire [ADC_BITS-1:0]      code2,
    output wire signed [CUR_W-1:0]  cur0,
    output wire signed [CUR_W-1:0]  cur1,
    output wire signed [CUR_W-1:0]  cur2,
    output wire                     sat,
    output wire                     frame_err,
    input  wire [ADC_BITS-1:0]      oc_thr,
    output wire                     oc,
    output wire [2:0]               oc_ch,
    input  wire [2:0]               off_we,
    input  wire [ADC_BITS-1:0]      off_wdata,
    output wire [ADC_BITS-1:0]      offset0,
    output wire [ADC_BITS-1:0]      offset1,
    output wire [ADC_BITS-1:0]      offset2,
    input  wire                     cal_start,
    output wire                     cal_busy,
    output wire                     cal_done,
    // slave side
    input  wire [ADC_BITS-1:0]      s_code0,
    input  wire [ADC_BITS-1:0]      s_code1,
    input  wire [ADC_BITS-1:0]      s_code2,
    input  wire [3*LEAD_ZEROS-1:0]  s_lead
);
    adc_spi #(
        .ADC_BITS(ADC_BITS), .FRAME_BITS(FRAME_BITS), .LEAD_ZEROS(LEAD_ZEROS),
        .SCLK_DIV(SCLK_DIV), .SAMPLE_DELAY(SAMPLE_DELAY), .CS_QUIET(CS_QUIET),
        .CAL_LOG2(CAL_LOG2), .CUR_W(CUR_W), .MISS_W(MISS_W), .OFFSET_RESET(OFFSET_RESET)
    ) u_dut (
        .clk(clk), .rst(rst), .trig(trig), .busy(busy), .trig_miss(trig_miss), .miss_cnt(miss_cnt),
        .cs_n(cs_n), .sclk(sclk), .miso(miso),
        .valid(valid), .code0(code0), .code1(code1), .code2(code2),
        .cur0(cur0), .cur1(cur1), .cur2(cur2), .sat(sat), .frame_err(frame_err),
        .oc_thr(oc_thr), .oc(oc), .oc_ch(oc_ch),
        .off_we(off_we), .off_wdata(off_wdata), .offset0(offset0), .offset1(offset1), .offset2(offset2),
        .cal_start(cal_start), .cal_busy(cal_busy), .cal_done(cal_done)
    );

    adc_spi_slave #(
        .ADC_BITS(ADC_BITS), .FRAME_BITS(FRAME_BITS), .LEAD_ZEROS(LEAD_ZEROS),
        .T_HOLD_PS(T_HOLD_PS), .T_OUT_PS(T_OUT_PS)
    ) u_slave (
        .sclk(sclk), .cs_n(cs_n), .code0(s_code0), .code1(s_code1), .code2(s_code2),
        .lead(s_lead), .miso(miso)
    );
endmodule
`default_nettype wire
