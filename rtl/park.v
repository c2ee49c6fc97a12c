// park: forward Park transform (paper 000 eq. 33) of the alpha-beta currents.
//
//   i_d =  cos * i_alpha + sin * i_beta
//   i_q = -sin * i_alpha + cos * i_beta
//   Each output: exact sum of two 18x18 products, one round-half-up by TRIG_FRAC bits,
//   saturation to I_W bits (sat pulse).  Bit-exact model: gen/empc/rtlmodel/park.py.
// Ports:
//   start                 1-cycle request, inputs sampled in that cycle; ignored while busy
//   i_alpha, i_beta       signed I_W (18) bit, Q.4 in ADC LSB (from clarke)
//   sin_in, cos_in        signed TRIG_W (18) bit, 1.0 = 2^TRIG_FRAC (from sincos)
//   busy                  high from the cycle after start up to the cycle before done
//   done                  1-cycle pulse, i_d/i_q/sat valid (held until the next done)
//   i_d, i_q              signed I_W bit, Q.4 in ADC LSB
//   sat                   1-cycle pulse with done if i_d or i_q saturated
// Parameters: I_W, TRIG_W, TRIG_FRAC (defaults from empc_formats.vh).
// Latency: 8 cycles (start cycle -> done cycle). Resources: 1 DSP48A1 (see park_core).
// Reset: outputs 0, not busy.
`default_nettype none
`include "empc_formats.vh"
module park #(
    parameter integer I_W       = `EMPC_I_W,
    parameter integer TRIG_W    = `EMPC_TRIG_W,
    parameter integer TRIG_FRAC = `EMPC_TRIG_FRAC
) (
    input  wire                     clk,
    input  wire                     rst,
    input  wire                     start,
    input  wire signed [I_W-1:0]    i_alpha,
    input  wire signed [I_W-1:0]    i_beta,
    input  wire signed [TRIG_W-1:0] sin_in,
    input  wire signed [TRIG_W-1:0] cos_in,
    output wire                     busy,
    output wire                     done,
    output wire signed [I_W-1:0]    i_d,
    output wire signed [I_W-1:0]    i_q,
    output wire                     sat
);
    park_core #(.W(I_W), .TW(TRIG_W), .TF(TRIG_FRAC), .INVERSE(0)) u_core (
        .clk(clk), .rst(rst), .start(start),
        .x0(i_alpha), .x1(i_beta), .sin_in(sin_in), .cos_in(cos_in),
        .busy(busy), .done(done), .y0(i_d), .y1(i_q), .sat(sat)
    );
endmodule
`default_nettype wire
