// inv_park: inverse Park transform (paper 000 eq. 34) of the dq voltages.
//
//   u_alpha = cos * u_d - sin * u_q
//   u_beta  = sin * u_d + cos * u_q
//   Each output: exact sum of two 18x18 products, one round-half-up by TRIG_FRAC bits,
//   saturation to V_W bits (sat pulse).  Bit-exact model: gen/empc/rtlmodel/inv_park.py.
// Ports:
//   start                 1-cycle request, inputs sampled in that cycle; ignored while busy
//   u_d, u_q              signed V_W (18) bit, Q.4 in PWM ticks at the nominal DC link
//   sin_in, cos_in        signed TRIG_W (18) bit, 1.0 = 2^TRIG_FRAC (from sincos)
//   busy                  high from the cycle after start up to the cycle before done
//   done                  1-cycle pulse, u_alpha/u_beta/sat valid (held until the next done)
//   u_alpha, u_beta       signed V_W bit, Q.4 in PWM ticks
//   sat                   1-cycle pulse with done if u_alpha or u_beta saturated
// Parameters: V_W, TRIG_W, TRIG_FRAC (defaults from empc_formats.vh).
// Latency: 8 cycles (start cycle -> done cycle). Resources: 1 DSP48A1 (see park_core).
// Reset: outputs 0, not busy.
`default_nettype none
`include "empc_formats.vh"
module inv_park #(
    parameter integer V_W       = `EMPC_V_W,
    parameter integer TRIG_W    = `EMPC_TRIG_W,
    parameter integer TRIG_FRAC = `EMPC_TRIG_FRAC
) (
    input  wire                     clk,
    input  wire                     rst,
    input  wire                     start,
    input  wire signed [V_W-1:0]    u_d,
    input  wire signed [V_W-1:0]    u_q,
    input  wire signed [TRIG_W-1:0] sin_in,
    input  wire signed [TRIG_W-1:0] cos_in,
    output wire                     busy,
    output wire                     done,
    output wire signed [V_W-1:0]    u_alpha,
    output wire signed [V_W-1:0]    u_beta,
    output wire                     sat
);
    park_core #(.W(V_W), .TW(TRIG_W), .TF(TRIG_FRAC), .INVERSE(1)) u_core (
        .clk(clk), .rst(rst), .start(start),
        .x0(u_d), .x1(u_q), .sin_in(sin_in), .cos_in(cos_in),
        .busy(busy), .done(done), .y0(u_alpha), .y1(u_beta), .sat(sat)
    );
endmodule
`default_nettype wire
