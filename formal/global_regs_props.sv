// global_regs_props: properties of the generated rtl/global_regs.v (issue 14; SymbiYosys,
// formal/global_regs.sby, run by flow/formal.py).  Every input of the block is free (the CPU
// port, the guard, the tick, the interrupt sets); only the first clock is a reset.  The
// references are built from the bus, not from the block's state.
//  G1  WDOG_TIMEOUT changes only in the clock after an accepted write of it: no axis live, and
//      WDOG_UNLOCK written with its key before (consumed by the next global write, timed out at
//      the UNLOCK_ARM-th tick); the block's unlock state equals the reference
//  G2  WDOG_TIMEOUT is never 0 (the watchdog cannot be disabled) nor above WDOG_TIMEOUT_MAX
//  G3  IRQ_STATUS write-1-to-clear loses no event: a set in the clock of any write (also the
//      write that clears that bit) is kept; a bit clears only by a write of 1 with no set
//  G4  the routing registers OUT_SEL0/1, ADC_SEL0/1, IN_SEL (out_route's R4, issue 16): reset to
//      today's pinout; change only in the clock after a write of them with route_locked low (no axis
//      live, a build that routes: lx_rocon_top ties it high without out_route) and (OUT_SEL)
//      every code 0..3 EMPC_ROUTE_AXES, then to exactly the written fields (whole word or nothing);
//      any other write of them is refused (wr_refused); out_sel*_wr pulse exactly on accepted writes
`default_nettype none
`include "empc_regs.vh"
module global_regs_props (
    input wire        clk,
    input wire        rst,
    input wire        reg_wr,
    input wire        reg_rd,
    input wire [7:0]  reg_addr,
    input wire [31:0] reg_wdata,
    input wire [31:0] time_cnt,
    input wire        irq_status_period_set,
    input wire        irq_status_fault_set,
    input wire        bridges_live,
    input wire        route_locked,
    input wire        caps_route,
    input wire        wdog_unlock_tick,
    input wire [2:0]  route_status_mapped0,
    input wire [2:0]  route_status_mapped1,
    input wire [2:0]  route_status_mapped2,
    input wire [2:0]  route_status_mapped3,
    input wire        route_status_bad_sel
);
    wire [31:0] reg_rdata, scratch;
    wire [`EMPC_G_WDOG_TIMEOUT_W-1:0] wdog_timeout;
    wire wdog_kick, irq_status_period, irq_status_fault, wr_refused;
    wire [1:0] irq_enable;
    wire [`EMPC_UNLOCK_ARM_W-1:0] armed;
    wire [`EMPC_G_OUT_SEL0_OUT0_W-1:0] out_sel0_out0;
    wire [`EMPC_G_OUT_SEL0_OUT1_W-1:0] out_sel0_out1;
    wire [`EMPC_G_OUT_SEL0_OUT2_W-1:0] out_sel0_out2;
    wire [`EMPC_G_OUT_SEL0_OUT3_W-1:0] out_sel0_out3;
    wire [`EMPC_G_OUT_SEL0_OUT4_W-1:0] out_sel0_out4;
    wire [`EMPC_G_OUT_SEL0_OUT5_W-1:0] out_sel0_out5;
    wire [`EMPC_G_OUT_SEL0_OUT6_W-1:0] out_sel0_out6;
    wire [`EMPC_G_OUT_SEL0_OUT7_W-1:0] out_sel0_out7;
    wire [`EMPC_G_OUT_SEL1_OUT8_W-1:0] out_sel1_out8;
    wire [`EMPC_G_OUT_SEL1_OUT9_W-1:0] out_sel1_out9;
    wire [`EMPC_G_OUT_SEL1_OUT10_W-1:0] out_sel1_out10;
    wire [`EMPC_G_OUT_SEL1_OUT11_W-1:0] out_sel1_out11;
    wire [`EMPC_G_OUT_SEL1_OUT12_W-1:0] out_sel1_out12;
    wire [`EMPC_G_OUT_SEL1_OUT13_W-1:0] out_sel1_out13;
    wire [`EMPC_G_OUT_SEL1_OUT14_W-1:0] out_sel1_out14;
    wire [`EMPC_G_OUT_SEL1_OUT15_W-1:0] out_sel1_out15;
    wire [`EMPC_G_ADC_SEL0_AX0_A_W-1:0] adc_sel0_ax0_a;
    wire [`EMPC_G_ADC_SEL0_AX0_B_W-1:0] adc_sel0_ax0_b;
    wire [`EMPC_G_ADC_SEL0_AX0_C_W-1:0] adc_sel0_ax0_c;
    wire [`EMPC_G_ADC_SEL0_AX1_A_W-1:0] adc_sel0_ax1_a;
    wire [`EMPC_G_ADC_SEL0_AX1_B_W-1:0] adc_sel0_ax1_b;
    wire [`EMPC_G_ADC_SEL0_AX1_C_W-1:0] adc_sel0_ax1_c;
    wire [`EMPC_G_ADC_SEL1_AX2_A_W-1:0] adc_sel1_ax2_a;
    wire [`EMPC_G_ADC_SEL1_AX2_B_W-1:0] adc_sel1_ax2_b;
    wire [`EMPC_G_ADC_SEL1_AX2_C_W-1:0] adc_sel1_ax2_c;
    wire [`EMPC_G_ADC_SEL1_AX3_A_W-1:0] adc_sel1_ax3_a;
    wire [`EMPC_G_ADC_SEL1_AX3_B_W-1:0] adc_sel1_ax3_b;
    wire [`EMPC_G_ADC_SEL1_AX3_C_W-1:0] adc_sel1_ax3_c;
    wire [`EMPC_G_IN_SEL_ENC0_W-1:0] in_sel_enc0;
    wire [`EMPC_G_IN_SEL_ENC1_W-1:0] in_sel_enc1;
    wire [`EMPC_G_IN_SEL_ENC2_W-1:0] in_sel_enc2;
    wire [`EMPC_G_IN_SEL_ENC3_W-1:0] in_sel_enc3;
    wire [`EMPC_G_IN_SEL_HALL0_W-1:0] in_sel_hall0;
    wire [`EMPC_G_IN_SEL_HALL1_W-1:0] in_sel_hall1;
    wire [`EMPC_G_IN_SEL_HALL2_W-1:0] in_sel_hall2;
    wire [`EMPC_G_IN_SEL_HALL3_W-1:0] in_sel_hall3;
    wire out_sel0_wr, out_sel1_wr;
    global_regs dut (
        .clk(clk), .rst(rst), .reg_wr(reg_wr), .reg_rd(reg_rd), .reg_addr(reg_addr), .reg_wdata(reg_wdata),
        .reg_rdata(reg_rdata), .caps_naxes(4'd1), .caps_horizon(4'd4), .caps_img_layout(8'd2),
        .caps_pwm_per_control(8'd5), .caps_complementary(1'b0), .caps_route(caps_route), .route_locked(route_locked), .pwm_half(32'd2500), .scratch(scratch),
        .wdog_timeout(wdog_timeout), .wdog_kick(wdog_kick), .time_cnt(time_cnt),
        .irq_status_period(irq_status_period), .irq_status_period_set(irq_status_period_set),
        .irq_status_fault(irq_status_fault), .irq_status_fault_set(irq_status_fault_set),
        .irq_enable(irq_enable),
        .out_sel0_out0(out_sel0_out0), .out_sel0_out1(out_sel0_out1), .out_sel0_out2(out_sel0_out2),
        .out_sel0_out3(out_sel0_out3), .out_sel0_out4(out_sel0_out4), .out_sel0_out5(out_sel0_out5),
        .out_sel0_out6(out_sel0_out6), .out_sel0_out7(out_sel0_out7), .out_sel1_out8(out_sel1_out8),
        .out_sel1_out9(out_sel1_out9), .out_sel1_out10(out_sel1_out10), .out_sel1_out11(out_sel1_out11),
        .out_sel1_out12(out_sel1_out12), .out_sel1_out13(out_sel1_out13), .out_sel1_out14(out_sel1_out14),
        .out_sel1_out15(out_sel1_out15), .adc_sel0_ax0_a(adc_sel0_ax0_a), .adc_sel0_ax0_b(adc_sel0_ax0_b),
        .adc_sel0_ax0_c(adc_sel0_ax0_c), .adc_sel0_ax1_a(adc_sel0_ax1_a), .adc_sel0_ax1_b(adc_sel0_ax1_b),
        .adc_sel0_ax1_c(adc_sel0_ax1_c), .adc_sel1_ax2_a(adc_sel1_ax2_a), .adc_sel1_ax2_b(adc_sel1_ax2_b),
        .adc_sel1_ax2_c(adc_sel1_ax2_c), .adc_sel1_ax3_a(adc_sel1_ax3_a), .adc_sel1_ax3_b(adc_sel1_ax3_b),
        .adc_sel1_ax3_c(adc_sel1_ax3_c), .in_sel_enc0(in_sel_enc0), .in_sel_enc1(in_sel_enc1),
        .in_sel_enc2(in_sel_enc2), .in_sel_enc3(in_sel_enc3), .in_sel_hall0(in_sel_hall0),
        .in_sel_hall1(in_sel_hall1), .in_sel_hall2(in_sel_hall2), .in_sel_hall3(in_sel_hall3),
        .out_sel0_wr(out_sel0_wr), .out_sel1_wr(out_sel1_wr), .route_status_mapped0(route_status_mapped0),
        .route_status_mapped1(route_status_mapped1), .route_status_mapped2(route_status_mapped2),
        .route_status_mapped3(route_status_mapped3), .route_status_bad_sel(route_status_bad_sel),
        .bridges_live(bridges_live), .wdog_unlock_tick(wdog_unlock_tick),
        .wdog_unlock_armed(armed), .wr_refused(wr_refused));

    reg f_pv = 1'b0;
    always @(posedge clk) f_pv <= 1'b1;
    always @(*) if (!f_pv) assume(rst);

    localparam integer AW = `EMPC_UNLOCK_ARM_W;
    localparam [AW-1:0] F_ARM = `EMPC_UNLOCK_ARM;
    reg [AW-1:0] f_arm;
    always @(posedge clk) begin
        if (rst)          f_arm <= {AW{1'b0}};
        else if (reg_wr)  f_arm <= (reg_addr == `EMPC_G_WDOG_UNLOCK && reg_wdata[15:0] == `EMPC_UNLOCK_KEY)
                                   ? F_ARM : {AW{1'b0}};
        else if (wdog_unlock_tick && f_arm != 0) f_arm <= f_arm - 1'b1;
    end
    reg p_rst, p_wr, p_live, p_lock, p_arm, p_ps, p_fs, p_ip, p_if;
    reg [7:0] p_addr;
    reg [31:0] p_wdata;
    reg [`EMPC_G_WDOG_TIMEOUT_W-1:0] p_to;
    always @(posedge clk) begin
        p_rst <= rst; p_wr <= reg_wr; p_live <= bridges_live; p_lock <= route_locked; p_arm <= (f_arm != 0);
        p_addr <= reg_addr; p_wdata <= reg_wdata; p_to <= wdog_timeout;
        p_ps <= irq_status_period_set; p_fs <= irq_status_fault_set;
        p_ip <= irq_status_period; p_if <= irq_status_fault;
    end
    wire f_go = f_pv && !p_rst;
    wire p_irqw = p_wr && p_addr == `EMPC_G_IRQ_STATUS;
    always @(*) if (f_go) begin
        assert(armed == f_arm);                                                          // G1
        if (wdog_timeout != p_to)
            assert(p_wr && p_addr == `EMPC_G_WDOG_TIMEOUT && !p_live && p_arm);          // G1
        assert(wdog_timeout != 0);                                                       // G2
        // G3: the bit after the edge: set, or kept, unless this clock's write cleared it
        assert(irq_status_period == (p_ps || (p_ip && !(p_irqw && p_wdata[`EMPC_G_IRQ_STATUS_PERIOD]))));
        assert(irq_status_fault == (p_fs || (p_if && !(p_irqw && p_wdata[`EMPC_G_IRQ_STATUS_FAULT]))));
    end

    // G4 (out_route's R4): the routing words, rebuilt from the field ports in the layout of
    // docs/registers.md (every field starts on a nibble), change only through an accepted write
    // (caps_route is only read back: free)
    localparam [31:0] M_OUT = 32'hffffffff, M_ADC = 32'h00ffffff, M_IN = 32'h33337777;   // field bits
    localparam integer NPAIR = `EMPC_ROUTE_AXES * `EMPC_ROUTE_PHASES;
    wire [31:0] w_o0 = {out_sel0_out7, out_sel0_out6, out_sel0_out5, out_sel0_out4, out_sel0_out3, out_sel0_out2,
                        out_sel0_out1, out_sel0_out0};
    wire [31:0] w_o1 = {out_sel1_out15, out_sel1_out14, out_sel1_out13, out_sel1_out12, out_sel1_out11,
                        out_sel1_out10, out_sel1_out9, out_sel1_out8};
    wire [31:0] w_a0 = {8'd0, adc_sel0_ax1_c, adc_sel0_ax1_b, adc_sel0_ax1_a, adc_sel0_ax0_c, adc_sel0_ax0_b,
                        adc_sel0_ax0_a};
    wire [31:0] w_a1 = {8'd0, adc_sel1_ax3_c, adc_sel1_ax3_b, adc_sel1_ax3_a, adc_sel1_ax2_c, adc_sel1_ax2_b,
                        adc_sel1_ax2_a};
    wire [31:0] w_in = {2'd0, in_sel_hall3, 2'd0, in_sel_hall2, 2'd0, in_sel_hall1, 2'd0, in_sel_hall0,
                        1'd0, in_sel_enc3, 1'd0, in_sel_enc2, 1'd0, in_sel_enc1, 1'd0, in_sel_enc0};
    reg [31:0] p_o0, p_o1, p_a0, p_a1, p_in;
    always @(posedge clk) begin
        p_o0 <= w_o0; p_o1 <= w_o1; p_a0 <= w_a0; p_a1 <= w_a1; p_in <= w_in;
    end
    // an OUT_SEL word is legal when every code names a routable pair or off
    function legal_out(input [31:0] w);
        integer i;
        begin
            legal_out = 1'b1;
            for (i = 0; i < 32 / `EMPC_ROUTE_NIB; i = i + 1) if (w[`EMPC_ROUTE_NIB*i +: `EMPC_ROUTE_NIB] > NPAIR) legal_out = 1'b0;
        end
    endfunction
    wire ok_o0 = p_wr && p_addr == `EMPC_G_OUT_SEL0 && !p_lock && legal_out(p_wdata);
    wire ok_o1 = p_wr && p_addr == `EMPC_G_OUT_SEL1 && !p_lock && legal_out(p_wdata);
    wire ok_a0 = p_wr && p_addr == `EMPC_G_ADC_SEL0 && !p_lock;
    wire ok_a1 = p_wr && p_addr == `EMPC_G_ADC_SEL1 && !p_lock;
    wire ok_in = p_wr && p_addr == `EMPC_G_IN_SEL && !p_lock;
    always @(*) if (f_pv && p_rst) begin                                                  // G4: reset map
        assert(w_o0 == `EMPC_G_OUT_SEL0_RESET && w_o1 == `EMPC_G_OUT_SEL1_RESET);
        assert(w_a0 == `EMPC_G_ADC_SEL0_RESET && w_a1 == `EMPC_G_ADC_SEL1_RESET && w_in == `EMPC_G_IN_SEL_RESET);
        assert(!out_sel0_wr && !out_sel1_wr);
    end
    always @(*) if (f_go) begin
        // G4: a word changes only by an accepted write (no axis live, every code legal), and then to the
        // written fields; a write of it that is not accepted is refused and changes nothing
        assert(w_o0 == (ok_o0 ? (p_wdata & M_OUT) : p_o0));
        assert(w_o1 == (ok_o1 ? (p_wdata & M_OUT) : p_o1));
        assert(w_a0 == (ok_a0 ? (p_wdata & M_ADC) : p_a0));
        assert(w_a1 == (ok_a1 ? (p_wdata & M_ADC) : p_a1));
        assert(w_in == (ok_in ? (p_wdata & M_IN) : p_in));
        if (p_wr && (p_addr == `EMPC_G_OUT_SEL0 || p_addr == `EMPC_G_OUT_SEL1 || p_addr == `EMPC_G_ADC_SEL0
                     || p_addr == `EMPC_G_ADC_SEL1 || p_addr == `EMPC_G_IN_SEL))
            assert(wr_refused == !(ok_o0 || ok_o1 || ok_a0 || ok_a1 || ok_in));
        // the write pulses that restart out_route's mapped scan: exactly the accepted OUT_SEL writes
        assert(out_sel0_wr == ok_o0 && out_sel1_wr == ok_o1);
    end
`ifdef GREGS_COVER
    always @(*) if (f_go) cover(wdog_timeout != p_to);
    always @(*) if (f_go) cover(out_sel1_wr && w_o1 != p_o1);
`endif
    wire unused = &{1'b0, reg_rdata, scratch, wdog_kick, irq_enable};
endmodule
`default_nettype wire
