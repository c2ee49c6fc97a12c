// clk_mon: loss-of-clock monitor for the fabric clock, run from an independent oscillator.
//
// The fabric clock (PLL output) is watched from the FPGA's own configuration oscillator:
// under SYNTHESIS the CFGMCLK output of STARTUP_SPARTAN6 (UG380, "Configuration internal
// oscillator clock output", nominal 50 MHz; it needs neither the board oscillator nor the
// PLL).  In simulation the same monitor runs from `osc_sim`, a register no RTL drives
// (initial 0): a testbench that wants the monitor makes it toggle (cocotb:
// Clock(dut.<path>.u_clkmon.osc_sim, ...)); left alone it never declares the clock dead.
// Only the oscillator source differs: the monitor logic is the same in both.
//
// clk domain: a free-running DIV_BITS-bit counter whose top bit `tgl` toggles every
// 2**(DIV_BITS-1) clocks, and `armed` (1 from the first clock with rst low: the start-up
// before the first PLL lock and a reset are not a clock loss).
// osc domain: tgl and armed through a sync_2ff (the named crossing), an edge detector, and
// a LIMIT_BITS-bit counter of osc cycles since the last tgl edge, saturating at
// 2**LIMIT_BITS - 1; `dead` = armed and the counter saturated, registered (a flip-flop:
// no glitch on the asynchronous preset it drives in out_kill).
//
// Ports: clk, rst (fabric clock, synchronous reset); dead (osc domain, asynchronous to
//   clk: 1 while no tgl edge has been seen for 2**LIMIT_BITS - 1 osc cycles).
// Parameters: DIV_BITS (>= 2), LIMIT_BITS (>= 2).
// Latency (defaults 3 / 4): a clock that stops is declared dead at most
//   2 (sync) + 1 (edge) + 15 (count) + 1 (dead register) = 19 osc cycles after its last
//   edge (380 ns at 50 MHz, 760 ns at 25 MHz).  No false trip while the fabric clock runs
//   faster than 2**(DIV_BITS-1) / ((2**LIMIT_BITS - 3) osc cycles) = 4 clocks per 13 osc
//   cycles, i.e. f_clk > 0.31 f_osc (31 MHz for f_osc = 100 MHz, twice the nominal
//   CFGMCLK): 100 MHz has a margin of 3.2 at the fastest oscillator assumed.
// Reset: rst clears the clk-domain counter and `armed`; the osc domain has no reset (it
//   must work when rst cannot be generated): initial values 0 (FPGA INIT), and a disarmed
//   monitor clears its counter and `dead` within 3 osc cycles.
// Resources: 5 flip-flops on clk, 10 on osc, about 8 LUTs; STARTUP_SPARTAN6 (one per
//   device: instantiate clk_mon once) and one global clock buffer for CFGMCLK.
// Two clock domains in one module on purpose: it is a crossing monitor (like sync_2ff).
`default_nettype none
module clk_mon #(
    parameter integer DIV_BITS = 3,
    parameter integer LIMIT_BITS = 4
) (
    input  wire clk,
    input  wire rst,
    output wire dead
);
    // ---------------- independent oscillator ----------------
    wire osc;
`ifdef SYNTHESIS
    STARTUP_SPARTAN6 u_startup (
        .CFGCLK(), .CFGMCLK(osc), .EOS(), .CLK(1'b0), .GSR(1'b0), .GTS(1'b0), .KEYCLEARB(1'b1));
`else
    reg osc_sim;                    // simulation stand-in for CFGMCLK, driven by the testbench
    initial osc_sim = 1'b0;
    assign osc = osc_sim;
`endif

    // ---------------- fabric clock side ----------------
    reg [DIV_BITS-1:0] div;
    reg                armed;
    initial begin
        div = {DIV_BITS{1'b0}};
        armed = 1'b0;
    end
    always @(posedge clk) begin
        if (rst) begin
            div   <= {DIV_BITS{1'b0}};
            armed <= 1'b0;
        end else begin
            div   <= div + 1'b1;
            armed <= 1'b1;
        end
    end

    // ---------------- oscillator side ----------------
    wire tgl_o, armed_o;
    sync_2ff #(.WIDTH(2)) u_sync (.clk(osc), .rst(1'b0), .d({armed, div[DIV_BITS-1]}), .q({armed_o, tgl_o}));
    reg                  tgl_p, dead_r;
    reg [LIMIT_BITS-1:0] cnt;
    initial begin
        tgl_p = 1'b0;
        dead_r = 1'b0;
        cnt = {LIMIT_BITS{1'b0}};
    end
    always @(posedge osc) begin
        tgl_p <= tgl_o;
        if (!armed_o || tgl_o != tgl_p) cnt <= {LIMIT_BITS{1'b0}};
        else if (!(&cnt))               cnt <= cnt + 1'b1;
        dead_r <= armed_o && (&cnt);
    end
    assign dead = dead_r;
endmodule
`default_nettype wire
