// adc_spi_axes_tb: simulation-only wrapper for tb/test_adc_spi_axes.py: adc_spi with NAXES > 1
// (one SCLK, one CS) wired pin-to-pin to NAXES adc_spi_slave instances (three ADC models each,
// slave a on miso[3a +: 3]).  All master inputs are brought out; the master's outputs are
// concatenated into `mon` (one read per clock in the test): bits 3:0 = {sclk, fvalid, busy, cs_n},
// then axis a's fields at 4 + a*AXW (field order in tb/test_adc_spi_axes.py axis_fields, LSB
// first).  The slaves' codes and lead-bit patterns are s_code (axis a, phase i at
// [(3a+i)*ADC_BITS +: ADC_BITS]) and s_lead (at [(3a+i)*LEAD_ZEROS +: LEAD_ZEROS]); monitors
// as g_sl[a].u_slave.*.
`default_nettype none
`timescale 1ns / 1ps
module adc_spi_axes_tb #(
    parameter integer NAXES          = 2,
    parameter integer STAGGER        = 370,
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
    parameter integer PSW = ADC_BITS + 1 + PCNT_W,
    parameter integer AXW = 14 + MISS_W + 6 * ADC_BITS + 3 * CUR_W + 3 * PSW + PCNT_W,
    parameter integer MON_W = 4 + NAXES * AXW
) (
    input  wire                         clk,
    input  wire                         rst,
    input  wire [NAXES-1:0]             period_start,
    input  wire [NAXES-1:0]             trig,
    input  wire [NAXES-1:0]             bridges_on,
    input  wire [NAXES*ADC_BITS-1:0]    oc_thr,
    input  wire [NAXES*ADC_BITS-1:0]    sum_thr,
    input  wire [3*NAXES-1:0]           off_we,
    input  wire [NAXES*ADC_BITS-1:0]    off_wdata,
    input  wire [NAXES-1:0]             cal_start,
    input  wire [NAXES-1:0]             refused_clear,
    output wire [MON_W-1:0]             mon,
    output wire                         cs_n,
    output wire                         sclk,
    output wire [3*NAXES-1:0]           miso,
    // slave side
    input  wire [3*NAXES*ADC_BITS-1:0]  s_code,
    input  wire [3*NAXES*LEAD_ZEROS-1:0] s_lead
);
    wire                       busy, fvalid;
    wire [NAXES-1:0]           trig_miss, frame_err, oc, sum_err, stuck, frozen, valid, sat;
    wire [NAXES-1:0]           cal_busy, cal_done, refused;
    wire [NAXES*MISS_W-1:0]    miss_cnt;
    wire [NAXES*ADC_BITS-1:0]  code0, code1, code2, offset0, offset1, offset2;
    wire [3*NAXES-1:0]         oc_ch;
    wire [NAXES*CUR_W-1:0]     cur0, cur1, cur2;
    wire [NAXES*PSW-1:0]       psum0, psum1, psum2;
    wire [NAXES*PCNT_W-1:0]    pcount;

    adc_spi #(
        .ADC_BITS(ADC_BITS), .FRAME_BITS(FRAME_BITS), .LEAD_ZEROS(LEAD_ZEROS), .SCLK_DIV(SCLK_DIV),
        .SAMPLE_DELAY(SAMPLE_DELAY), .CS_QUIET(CS_QUIET), .HALF_PERIOD(HALF_PERIOD), .AVG_LOG2(AVG_LOG2),
        .FRAME_PERIOD(FRAME_PERIOD), .CAL_LOG2(CAL_LOG2), .CUR_W(CUR_W), .MISS_W(MISS_W),
        .OFFSET_RESET(OFFSET_RESET), .PCNT_W(PCNT_W), .SUM_PERSIST(SUM_PERSIST), .STUCK_PERSIST(STUCK_PERSIST),
        .FROZEN_PERIODS(FROZEN_PERIODS), .NAXES(NAXES), .STAGGER(STAGGER)
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

    assign mon[3:0] = {sclk, fvalid, busy, cs_n};
    genvar a;
    generate
        for (a = 0; a < NAXES; a = a + 1) begin : g_sl
            assign mon[4 + a * AXW +: AXW] = {
                refused[a], cal_done[a], cal_busy[a],
                offset2[a * ADC_BITS +: ADC_BITS], offset1[a * ADC_BITS +: ADC_BITS], offset0[a * ADC_BITS +: ADC_BITS],
                pcount[a * PCNT_W +: PCNT_W], psum2[a * PSW +: PSW], psum1[a * PSW +: PSW], psum0[a * PSW +: PSW],
                sat[a], cur2[a * CUR_W +: CUR_W], cur1[a * CUR_W +: CUR_W], cur0[a * CUR_W +: CUR_W],
                valid[a], frozen[a], stuck[a], sum_err[a], oc_ch[3 * a +: 3], oc[a], frame_err[a],
                code2[a * ADC_BITS +: ADC_BITS], code1[a * ADC_BITS +: ADC_BITS], code0[a * ADC_BITS +: ADC_BITS],
                miss_cnt[a * MISS_W +: MISS_W], trig_miss[a]};
            adc_spi_slave #(
                .ADC_BITS(ADC_BITS), .FRAME_BITS(FRAME_BITS), .LEAD_ZEROS(LEAD_ZEROS),
                .T_HOLD_PS(T_HOLD_PS), .T_OUT_PS(T_OUT_PS)
            ) u_slave (
                .sclk(sclk), .cs_n(cs_n),
                .code0(s_code[(3 * a + 0) * ADC_BITS +: ADC_BITS]),
                .code1(s_code[(3 * a + 1) * ADC_BITS +: ADC_BITS]),
                .code2(s_code[(3 * a + 2) * ADC_BITS +: ADC_BITS]),
                .lead(s_lead[3 * a * LEAD_ZEROS +: 3 * LEAD_ZEROS]), .miso(miso[3 * a +: 3])
            );
        end
    endgenerate
endmodule
`default_nettype wire
