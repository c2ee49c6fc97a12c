// adc_ripple: simulation-only source of per-frame ADC codes for the co-simulation:
// the period's phase-current codes from Python plus PWM ripple and noise, so that every
// back-to-back frame differs (the frozen-ADC check must not trip) while the Python side
// still predicts the controller's window mean exactly (tb/test_closed_loop.py mirrors
// this function bit for bit: AdcRipple.code).
//
// tau = clock cycle relative to the PWM centre of the current period (period_start is in
// cycle -HALF_PERIOD); it advances on the falling clock edge, so the codes are stable
// around the rising edge at which the ADC slave samples them (CS falling).  Code of
// channel i at tau:
//   clamp(base_i + r_i(tau) + n_i(tau), 0, 2^ADC_BITS - 1), or inj_code if inj_en and
//   tau == inj_tau and i == inj_ch (a single-frame fault)
//   r_i(tau) = trunc(amp_i * u / (HALF_PERIOD/2)), u = tau for |tau| <= HALF_PERIOD/2,
//              else sign(tau) * (HALF_PERIOD - |tau|): the odd triangle of centre-aligned
//              PWM ripple (zero, i.e. the period's mean, at the centre and the boundaries)
//   n_i(tau) = (h mod (2*noise+1)) - noise, h = a 32-bit hash of (seed, tau, i)
//   or base_i exactly if hold[i] (a frozen or stuck channel: the fault co-simulations)
// Ports: clk, period_start (from the axis), base0..2, amp0..2 (signed), seed, noise (peak
// LSB), inj_*, hold; code0..2 to adc_spi_slave.
`default_nettype none
module adc_ripple #(
    parameter integer HALF_PERIOD = 2500,
    parameter integer ADC_BITS = 12
) (
    input  wire                 clk,
    input  wire                 period_start,
    input  wire [ADC_BITS-1:0]  base0,
    input  wire [ADC_BITS-1:0]  base1,
    input  wire [ADC_BITS-1:0]  base2,
    input  wire signed [15:0]   amp0,
    input  wire signed [15:0]   amp1,
    input  wire signed [15:0]   amp2,
    input  wire [31:0]          seed,
    input  wire [3:0]           noise,
    input  wire                 inj_en,
    input  wire signed [15:0]   inj_tau,
    input  wire [1:0]           inj_ch,
    input  wire [ADC_BITS-1:0]  inj_code,
    input  wire [2:0]           hold,
    output wire [ADC_BITS-1:0]  code0,
    output wire [ADC_BITS-1:0]  code1,
    output wire [ADC_BITS-1:0]  code2
);
    localparam integer HQ = HALF_PERIOD / 2;
    integer tau = 0;
    always @(negedge clk) tau <= period_start ? -HALF_PERIOD : tau + 1;

    function [ADC_BITS-1:0] f;
        input integer t;
        input [ADC_BITS-1:0] base;
        input signed [15:0] amp;
        input integer ch;
        integer u, at, r, n, v, na, b, a;
        reg [31:0] h;
        begin
            na = noise;
            b = base;
            a = amp;
            at = (t < 0) ? -t : t;
            u = (at <= HQ) ? t : ((t < 0) ? -(HALF_PERIOD - at) : (HALF_PERIOD - at));
            r = (a * u) / HQ;                                    // signed integer division: toward zero
            h = seed ^ (t * 32'd2654435761) ^ (ch * 32'd40503);  // 32-bit unsigned, wraps
            h = (h ^ (h >> 15)) * 32'd2246822519;
            h = h ^ (h >> 13);
            n = h % (2 * na + 1);
            n = n - na;
            v = b + r + n;
            if (hold[ch]) f = base;
            else if (inj_en && t == inj_tau && ch == inj_ch) f = inj_code;
            else f = (v < 0) ? {ADC_BITS{1'b0}} : (v > (1 << ADC_BITS) - 1) ? {ADC_BITS{1'b1}} : v[ADC_BITS-1:0];
        end
    endfunction

    assign code0 = f(tau, base0, amp0, 0);
    assign code1 = f(tau, base1, amp1, 1);
    assign code2 = f(tau, base2, amp2, 2);
endmodule
`default_nettype wire
