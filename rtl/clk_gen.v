// clk_gen: board clock -> 100 MHz fabric clock and a synchronous reset.
//
// Synthesis (`SYNTHESIS`, defined by Yosys and ISE): Spartan-6 PLL_BASE,
// CLKIN_HZ * MULT / DIV (default 50 MHz * 12 / 6 = 100 MHz, VCO 600 MHz), output on
// a BUFG.  Simulation: the fabric clock is clk_in itself (testbenches drive clk_in at
// the fabric rate) and `locked` rises after a few clocks.
// rst is asserted while the PLL is unlocked or rst_n_in is low, and released
// synchronously RST_HOLD clocks later (rst_n_in is asynchronous: synchronised).
// Latency: rst deasserts RST_HOLD + 2 clocks after lock and rst_n_in high.
`default_nettype none
module clk_gen #(
    parameter real    CLKIN_PERIOD_NS = 20.0,
    parameter integer MULT = 12,
    parameter integer DIV = 6,
    parameter integer RST_HOLD = 16
) (
    input  wire clk_in,
    input  wire rst_n_in,
    output wire clk,
    output reg  rst,
    output wire locked
);
`ifdef SYNTHESIS
    wire clkfb, clkout0;
    PLL_BASE #(
        .BANDWIDTH("OPTIMIZED"), .CLK_FEEDBACK("CLKFBOUT"), .COMPENSATION("INTERNAL"),
        .DIVCLK_DIVIDE(1), .CLKFBOUT_MULT(MULT), .CLKFBOUT_PHASE(0.0),
        .CLKOUT0_DIVIDE(DIV), .CLKOUT0_PHASE(0.0), .CLKOUT0_DUTY_CYCLE(0.5),
        .CLKIN_PERIOD(CLKIN_PERIOD_NS), .REF_JITTER(0.010)
    ) u_pll (
        .CLKIN(clk_in), .CLKFBIN(clkfb), .RST(1'b0), .CLKFBOUT(clkfb), .CLKOUT0(clkout0),
        .CLKOUT1(), .CLKOUT2(), .CLKOUT3(), .CLKOUT4(), .CLKOUT5(), .LOCKED(locked)
    );
    BUFG u_bufg (.I(clkout0), .O(clk));
`else
    reg [3:0] lock_cnt;
    initial lock_cnt = 4'd0;   // power-up value: this block makes the reset, it cannot use one
    assign clk = clk_in;
    assign locked = lock_cnt[3];
    always @(posedge clk_in) if (!lock_cnt[3]) lock_cnt <= lock_cnt + 4'd1;
`endif
    // rst_n_in and locked are asynchronous to clk: synchronise, then hold
    wire go;
    sync_2ff #(.WIDTH(1), .RESET_VALUE(1'b0)) u_sync (.clk(clk), .rst(1'b0), .d(rst_n_in & locked), .q(go));
    reg [$clog2(RST_HOLD+1)-1:0] hold;
    initial begin
        hold = 0;
        rst = 1'b1;
    end
    always @(posedge clk) begin
        if (!go) begin
            hold <= 0;
            rst <= 1'b1;
        end else if (hold != RST_HOLD[$clog2(RST_HOLD+1)-1:0]) begin
            hold <= hold + 1'b1;
            rst <= 1'b1;
        end else
            rst <= 1'b0;
    end
    wire unused = &{1'b0, CLKIN_PERIOD_NS > 0.0, MULT, DIV};
endmodule
`default_nettype wire
