// mpc_mul18: registered signed W x W multiply-add for the MPC core (one DSP48A1).
//
// p = a * b + c with registered operands (a, b, c: the DSP48A1's A/B/C registers) and a
// registered result (P register), so Yosys / ISE map it to exactly one DSP48A1 (multiplier
// plus post-adder) and nothing else: the MPC core keeps every multiplication inside this
// module.  c_clr clears the c register instead of loading c, ab_clr the a and b registers
// (the DSP's synchronous RSTC / RSTA, RSTB).
// Ports: a, b (signed W), c (signed PW), c_clr, ab_clr, p (signed PW); all synchronous to clk.
// Parameters: W operand width (default EMPC_OPW = 18, the DSP48A1 width), PW = EMPC_ACCW (48,
// the DSP48A1 post-adder width; |a * b + c| must stay below 2^(PW-1), true for all uses);
// CREG = 1: c registered here (the DSP's C register), 0: c is used as it comes (the caller
// registers it one clock ahead, e.g. in fabric flip-flops with per-field resets; c_clr unused).
// Latency: 2 clock cycles (a, b, c sampled at edge k, p valid after edge k+2; CREG = 0: c
// sampled at edge k+1).
// Reset: operand and result registers clear to 0.
`default_nettype none
`include "empc_formats.vh"
module mpc_mul18 #(
    parameter integer W = `EMPC_OPW,
    parameter integer PW = `EMPC_ACCW,
    parameter integer CREG = 1
) (
    input  wire                  clk,
    input  wire                  rst,
    input  wire signed [W-1:0]   a,
    input  wire signed [W-1:0]   b,
    input  wire signed [PW-1:0]  c,
    input  wire                  c_clr,
    input  wire                  ab_clr,
    output reg  signed [PW-1:0]  p
);
    reg signed [W-1:0]  a_r;
    reg signed [W-1:0]  b_r;
    reg signed [PW-1:0] c_r;
    always @(posedge clk) begin
        if (rst || ab_clr) begin
            a_r <= {W{1'b0}};
            b_r <= {W{1'b0}};
        end else begin
            a_r <= a;
            b_r <= b;
        end
        if (rst) p <= {PW{1'b0}};
        else     p <= a_r * b_r + c_r;
    end
    generate if (CREG != 0) begin : g_creg
        always @(posedge clk) begin
            if (rst || c_clr) c_r <= {PW{1'b0}};
            else              c_r <= c;
        end
    end else begin : g_cdir
        always @* c_r = c;
        wire unused_ok = &{1'b0, c_clr};
    end endgenerate
endmodule
`default_nettype wire
