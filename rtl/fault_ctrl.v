// fault_ctrl: sticky fault latch with a combinational trip output.
//
// Every cause input (level or single-clock pulse, synchronous to clk) sets
// its sticky bit in fault_latched at the next clock edge, masked or not, so
// the CPU always sees what happened.  `trip` forces the PWM safe state:
//   trip = |((fault_latched | cause_in) & mask)
// so it is high combinationally in the SAME clock in which a masked cause
// input is high (the PWM block's fault input sees it at once) and stays high
// from the next clock on through the latched bit until the bit is cleared.
// A latched bit whose mask bit is set later trips from that clock on.
// `clear` (pulse) clears only the bits whose cause is no longer present:
//   clear : fault_latched <= cause_in
//   else  : fault_latched <= fault_latched | cause_in
// (a cause that is still active keeps its bit; nothing is ever lost).
//
// Ports:
//   clk, rst        clock, synchronous active-high reset
//   cause_in        NCAUSE fault causes, level or pulse, synchronous, active high
//   mask            causes that trip the bridges (1 = trips)
//   clear           pulse: clear the latched bits whose cause has gone
//   fault_latched   sticky cause bits (registered)
//   trip            combinational: safe-state request
// Parameters:
//   NCAUSE          number of causes (mpc_axis: 10, the register map's AXIS FAULT bits:
//                   overcurrent, hall, encoder, watchdog, dclink, overrun, adc,
//                   adc_stuck, adc_sum, adc_frozen)
// Latency: trip 0 clocks (combinational from cause_in and mask); fault_latched
//   1 clock after the cause.
// Reset: fault_latched = 0 (trip then only follows cause_in & mask).
// Resources: NCAUSE flip-flops and a few LUTs; no DSP/BRAM.
`default_nettype none
module fault_ctrl #(
    parameter integer NCAUSE = 7
) (
    input  wire              clk,
    input  wire              rst,
    input  wire [NCAUSE-1:0] cause_in,
    input  wire [NCAUSE-1:0] mask,
    input  wire              clear,
    output reg  [NCAUSE-1:0] fault_latched,
    output wire              trip
);
    always @(posedge clk) begin
        if (rst)
            fault_latched <= {NCAUSE{1'b0}};
        else if (clear)
            fault_latched <= cause_in;
        else
            fault_latched <= fault_latched | cause_in;
    end

    assign trip = |((fault_latched | cause_in) & mask);
endmodule
`default_nettype wire
