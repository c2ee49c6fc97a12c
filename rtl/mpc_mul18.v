// mpc_mul18: registered signed W x W multiplier for the MPC core (one DSP48A1).
//
// p = a * b with registered operands and a registered product, so Yosys / ISE map
// it to exactly one DSP48A1 (A/B input registers, M or P register) and nothing
// else: the MPC core keeps every multiplication inside this module.
// Ports: a, b (signed W), p (signed 2W), all synchronous to clk.
// Parameters: W operand width (default EMPC_OPW = 18, the DSP48A1 width).
// Latency: 2 clock cycles (a, b sampled at edge k, p valid after edge k+2).
// Reset: operand and product registers clear to 0 (the DSP's RSTA/RSTB/RSTM).
`default_nettype none
`include "empc_formats.vh"
module mpc_mul18 #(
    parameter integer W = `EMPC_OPW
) (
    input  wire                  clk,
    input  wire                  rst,
    input  wire signed [W-1:0]   a,
    input  wire signed [W-1:0]   b,
    output reg  signed [2*W-1:0] p
);
    reg signed [W-1:0] a_r;
    reg signed [W-1:0] b_r;
    always @(posedge clk) begin
        if (rst) begin
            a_r <= {W{1'b0}};
            b_r <= {W{1'b0}};
            p   <= {(2*W){1'b0}};
        end else begin
            a_r <= a;
            b_r <= b;
            p   <= a_r * b_r;
        end
    end
endmodule
`default_nettype wire
