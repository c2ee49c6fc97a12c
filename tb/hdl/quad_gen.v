// quad_gen: simulation-only incremental-encoder emulator for the co-simulation.
//
// Python (cocotb) writes a target count once per half PWM period; this block
// walks its internal count towards the target one quadrature step every
// STEP_CLKS clocks (so the decoder's glitch filter sees clean edges) and drives
// A/B (x4 Gray sequence, count up = A leads... see irc_decoder: B leading counts up)
// and the index pulse while count mod CPR == 0 and idx_enable is high (the
// decoder ignores levels present at start-up, so the test raises idx_enable once
// the decoder is ready to get the first index edge).  Running every clock in
// Verilog keeps Python out of the per-clock loop.
// A/B: phase (a, b) = 00, 10, 11, 01 for count mod 4 = 0..3 (A leads B counting up).
`default_nettype none
module quad_gen #(
    parameter integer CPR = 4000,
    parameter integer STEP_CLKS = 16
) (
    input  wire        clk,
    input  wire        rst,
    input  wire [31:0] target,
    input  wire        idx_enable,
    output reg         a,
    output reg         b,
    output wire        idx,
    output reg  [31:0] count,
    output wire        at_target
);
    reg [15:0] tmr;
    wire signed [31:0] diff = target - count;
    assign at_target = (diff == 32'sd0);
    // count mod CPR == 0 for a signed 32-bit count (simulation only: % is fine here)
    wire signed [31:0] m = $signed(count) % CPR;
    assign idx = idx_enable && (m == 32'sd0);
    always @(posedge clk) begin
        if (rst) begin
            count <= 32'd0;
            tmr <= 16'd0;
            a <= 1'b0;
            b <= 1'b0;
        end else begin
            tmr <= (tmr == 16'd0) ? 16'd0 : tmr - 16'd1;
            if (tmr == 16'd0 && !at_target) begin
                count <= diff > 0 ? count + 32'd1 : count - 32'd1;
                tmr <= STEP_CLKS[15:0] - 16'd1;
            end
            {a, b} <= phase(count);
        end
    end
    function [1:0] phase;
        input [31:0] c;
        case (c[1:0])
            2'd0: phase = 2'b00;     // {a, b}
            2'd1: phase = 2'b10;
            2'd2: phase = 2'b11;
            default: phase = 2'b01;
        endcase
    endfunction
endmodule
`default_nettype wire
