// watchdog: CPU watchdog counting PWM-period ticks.
//
// The counter counts `tick` pulses (one per PWM period) since the last `kick`.
// `expired` goes high in the clock after the tick that makes the count reach
// `timeout` and stays high until the next `kick` (the fault latch downstream
// makes the fault itself sticky).  timeout = 0 disables the watchdog: counter
// and expired are held at 0, so enabling it later starts a fresh interval.
// If timeout is lowered below the current count, expired rises in the next
// clock (no tick needed).  Raising timeout does not clear expired; only kick
// (or timeout = 0, or reset) does.  A kick in the same clock as a tick wins
// (count 0).  The counter stops while expired, so it never overflows (it only
// counts while count < timeout <= 2**TW-1).
//
// Ports:
//   clk, rst   clock, synchronous active-high reset
//   tick       pulse per PWM period
//   kick       pulse: restart the interval, clear expired
//   timeout    interval in ticks, 0 = disabled
//   expired    level, registered
// Parameters:
//   TW         width of timeout and of the tick counter (16 for WDOG_TIMEOUT)
// Latency: expired rises 1 clock after the timeout-th tick; falls 1 clock after kick.
// Reset: count 0, expired 0.
// Resources: TW+1 flip-flops, one TW-bit incrementer and one
//   magnitude compare on carry chains (24 LUTs, 9 CARRY4 for TW = 16); no DSP/BRAM.
`default_nettype none
module watchdog #(
    parameter integer TW = 16
) (
    input  wire          clk,
    input  wire          rst,
    input  wire          tick,
    input  wire          kick,
    input  wire [TW-1:0] timeout,
    output reg           expired
);
    reg  [TW-1:0] count;
    // count_n = count + (tick && !expired); reach = count_n >= timeout, while not expired
    // (while expired the term is unused).  One magnitude compare on a carry chain: no carry
    // out of timeout + ~count_n (timeout - count_n - 1 < 0), with the tick multiplexer in
    // the same LUT per bit; count_n = count + tick, the incrementer is a carry chain too (an
    // equality count + 1 == timeout became a 16-bit LUT chain after the incrementer, 8 LUT
    // levels, the worst path of the top).  The wrap of count + 1 at count = 2**TW-1 is
    // harmless: count only gets there by an increment, which sets expired (2**TW-1 >=
    // timeout), and stays there only while expired.
    wire [TW-1:0] count_p1 = count + {{(TW-1){1'b0}}, 1'b1};
    wire [TW-1:0] count_n = tick ? count_p1 : count;
    wire [TW:0]   lt_c = {1'b0, timeout} + {1'b0, ~count_n};
    wire          reach = ~lt_c[TW];

    always @(posedge clk) begin
        if (rst || kick || timeout == {TW{1'b0}}) begin
            count   <= {TW{1'b0}};
            expired <= 1'b0;
        end else begin
            if (tick && !expired)
                count <= count_p1;
            if (reach)
                expired <= 1'b1;
        end
    end
endmodule
`default_nettype wire
