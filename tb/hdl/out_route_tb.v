// out_route_tb: simulation-only harness for tb/test_out_route.py: the generated global register
// block (rtl/global_regs.v, which stores and guards the routing registers) wired to out_route as the
// four-axis top will wire them: OUT_SEL / ADC_SEL / IN_SEL fields into the selects, the OUT_SEL
// write strobes into osel_wr, mapped / bad_sel back into ROUTE_STATUS.  The CPU port, the guard
// (bridges_live, also as the routing registers' route_locked: a build that routes), the pwm_center pairs, the trips and the board's input lines are the harness ports.
`default_nettype none
`timescale 1ns / 1ps
`include "empc_regs.vh"
module out_route_tb #(
    parameter integer NAXES = `EMPC_ROUTE_AXES,
    parameter integer NENC = `EMPC_ROUTE_ENC,      // a build with fewer board lines (bad_sel tests)
    parameter integer NHALL = `EMPC_ROUTE_HALL,
    parameter integer NADC = `EMPC_ROUTE_ADC
) (
    input  wire                           clk,
    input  wire                           rst,
    input  wire                           reg_wr,
    input  wire                           reg_rd,
    input  wire [7:0]                     reg_addr,
    input  wire [31:0]                    reg_wdata,
    output wire [31:0]                    reg_rdata,
    input  wire                           bridges_live,
    output wire                           wr_refused,
    input  wire [3*NAXES-1:0]             hi,
    input  wire [3*NAXES-1:0]             lo,
    input  wire [NAXES-1:0]               trip,
    output wire [`EMPC_ROUTE_OUTPUTS-1:0] pin_hi,
    output wire [`EMPC_ROUTE_OUTPUTS-1:0] pin_lo,
    input  wire [NADC-1:0]                miso,
    output wire [3*NAXES-1:0]             ax_miso,
    input  wire [NENC-1:0]                irc_a,
    input  wire [NENC-1:0]                irc_b,
    input  wire [NENC-1:0]                irc_idx,
    input  wire [NENC-1:0]                irc_mark,
    output wire [NAXES-1:0]               ax_irc_a,
    output wire [NAXES-1:0]               ax_irc_b,
    output wire [NAXES-1:0]               ax_irc_idx,
    output wire [NAXES-1:0]               ax_irc_mark,
    input  wire [3*NHALL-1:0]             hall,
    output wire [3*NAXES-1:0]             ax_hall,
    output wire [3*NAXES-1:0]             mapped,
    output wire                           bad_sel
);
    localparam integer SW = `EMPC_ROUTE_OUT_W, AW = `EMPC_ROUTE_ADC_W, EW = `EMPC_ROUTE_ENC_W,
                       HW = `EMPC_ROUTE_HALL_W, NA = `EMPC_ROUTE_AXES;
    wire [SW*`EMPC_ROUTE_OUTPUTS-1:0] osel;
    wire [1:0] osel_wr;
    wire [AW*3*NA-1:0] asel;
    wire [EW*NA-1:0] esel;
    wire [HW*NA-1:0] hsel;
    wire [3*NA-1:0] mapped_all;                    // ROUTE_STATUS.mapped: 0 for axes the build lacks
    generate
        if (NAXES < NA) begin : g_pad
            assign mapped_all = {{(3*(NA-NAXES)){1'b0}}, mapped};
        end else begin : g_full
            assign mapped_all = mapped;
        end
    endgenerate
    wire [31:0] scratch;
    wire [10:0] wdog_timeout;
    wire [1:0] irq_enable, armed;
    wire wdog_kick, irq_p, irq_f;
    global_regs u_regs (
        .clk(clk), .rst(rst), .reg_wr(reg_wr), .reg_rd(reg_rd), .reg_addr(reg_addr), .reg_wdata(reg_wdata),
        .reg_rdata(reg_rdata), .caps_naxes(4'd0), .caps_horizon(4'd0), .caps_img_layout(8'd0),
        .caps_pwm_per_control(8'd0), .caps_complementary(1'b0), .caps_route(1'b1),
        .route_locked(bridges_live), .pwm_half(32'd0), .scratch(scratch),
        .wdog_timeout(wdog_timeout), .wdog_kick(wdog_kick), .time_cnt(32'd0), .irq_status_period(irq_p),
        .irq_status_period_set(1'b0), .irq_status_fault(irq_f), .irq_status_fault_set(1'b0),
        .irq_enable(irq_enable),
        .out_sel0_out0(osel[0*SW +: SW]), .out_sel0_out1(osel[1*SW +: SW]), .out_sel0_out2(osel[2*SW +: SW]),
        .out_sel0_out3(osel[3*SW +: SW]), .out_sel0_out4(osel[4*SW +: SW]), .out_sel0_out5(osel[5*SW +: SW]),
        .out_sel0_out6(osel[6*SW +: SW]), .out_sel0_out7(osel[7*SW +: SW]), .out_sel1_out8(osel[8*SW +: SW]),
        .out_sel1_out9(osel[9*SW +: SW]), .out_sel1_out10(osel[10*SW +: SW]),
        .out_sel1_out11(osel[11*SW +: SW]), .out_sel1_out12(osel[12*SW +: SW]),
        .out_sel1_out13(osel[13*SW +: SW]), .out_sel1_out14(osel[14*SW +: SW]),
        .out_sel1_out15(osel[15*SW +: SW]), .out_sel0_wr(osel_wr[0]), .out_sel1_wr(osel_wr[1]),
        .adc_sel0_ax0_a(asel[0*AW +: AW]), .adc_sel0_ax0_b(asel[1*AW +: AW]), .adc_sel0_ax0_c(asel[2*AW +: AW]),
        .adc_sel0_ax1_a(asel[3*AW +: AW]), .adc_sel0_ax1_b(asel[4*AW +: AW]), .adc_sel0_ax1_c(asel[5*AW +: AW]),
        .adc_sel1_ax2_a(asel[6*AW +: AW]), .adc_sel1_ax2_b(asel[7*AW +: AW]), .adc_sel1_ax2_c(asel[8*AW +: AW]),
        .adc_sel1_ax3_a(asel[9*AW +: AW]), .adc_sel1_ax3_b(asel[10*AW +: AW]),
        .adc_sel1_ax3_c(asel[11*AW +: AW]), .in_sel_enc0(esel[0*EW +: EW]), .in_sel_enc1(esel[1*EW +: EW]),
        .in_sel_enc2(esel[2*EW +: EW]), .in_sel_enc3(esel[3*EW +: EW]), .in_sel_hall0(hsel[0*HW +: HW]),
        .in_sel_hall1(hsel[1*HW +: HW]), .in_sel_hall2(hsel[2*HW +: HW]), .in_sel_hall3(hsel[3*HW +: HW]),
        .route_status_mapped0(mapped_all[0*3 +: 3]), .route_status_mapped1(mapped_all[1*3 +: 3]),
        .route_status_mapped2(mapped_all[2*3 +: 3]), .route_status_mapped3(mapped_all[3*3 +: 3]),
        .route_status_bad_sel(bad_sel),
        .bridges_live(bridges_live), .wdog_unlock_tick(1'b0), .wdog_unlock_armed(armed), .wr_refused(wr_refused));
    out_route #(.NAXES(NAXES), .NENC(NENC), .NHALL(NHALL), .NADC(NADC)) dut (
        .clk(clk), .rst(rst), .osel(osel), .osel_wr(|osel_wr), .asel(asel[AW*3*NAXES-1:0]),
        .esel(esel[EW*NAXES-1:0]), .hsel(hsel[HW*NAXES-1:0]), .hi(hi), .lo(lo), .trip(trip),
        .pin_hi(pin_hi), .pin_lo(pin_lo), .miso(miso), .ax_miso(ax_miso), .irc_a(irc_a), .irc_b(irc_b),
        .irc_idx(irc_idx), .irc_mark(irc_mark), .ax_irc_a(ax_irc_a), .ax_irc_b(ax_irc_b),
        .ax_irc_idx(ax_irc_idx), .ax_irc_mark(ax_irc_mark), .hall(hall), .ax_hall(ax_hall),
        .mapped(mapped), .bad_sel(bad_sel));
endmodule
`default_nettype wire
