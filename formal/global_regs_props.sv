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
    input wire        wdog_unlock_tick
);
    wire [31:0] reg_rdata, scratch;
    wire [`EMPC_G_WDOG_TIMEOUT_W-1:0] wdog_timeout;
    wire wdog_kick, irq_status_period, irq_status_fault, wr_refused;
    wire [1:0] irq_enable;
    wire [`EMPC_UNLOCK_ARM_W-1:0] armed;
    global_regs dut (
        .clk(clk), .rst(rst), .reg_wr(reg_wr), .reg_rd(reg_rd), .reg_addr(reg_addr), .reg_wdata(reg_wdata),
        .reg_rdata(reg_rdata), .caps_naxes(4'd1), .caps_horizon(4'd4), .caps_img_layout(8'd2),
        .caps_pwm_per_control(8'd5), .caps_complementary(1'b0), .pwm_half(32'd2500), .scratch(scratch),
        .wdog_timeout(wdog_timeout), .wdog_kick(wdog_kick), .time_cnt(time_cnt),
        .irq_status_period(irq_status_period), .irq_status_period_set(irq_status_period_set),
        .irq_status_fault(irq_status_fault), .irq_status_fault_set(irq_status_fault_set),
        .irq_enable(irq_enable), .bridges_live(bridges_live), .wdog_unlock_tick(wdog_unlock_tick),
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
    reg p_rst, p_wr, p_live, p_arm, p_ps, p_fs, p_ip, p_if;
    reg [7:0] p_addr;
    reg [31:0] p_wdata;
    reg [`EMPC_G_WDOG_TIMEOUT_W-1:0] p_to;
    always @(posedge clk) begin
        p_rst <= rst; p_wr <= reg_wr; p_live <= bridges_live; p_arm <= (f_arm != 0);
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
`ifdef GREGS_COVER
    always @(*) if (f_go) cover(wdog_timeout != p_to);
`endif
    wire unused = &{1'b0, reg_rdata, scratch, wdog_kick, irq_enable, wr_refused};
endmodule
`default_nettype wire
