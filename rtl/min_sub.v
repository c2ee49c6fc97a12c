// min_sub: min-subtraction of the three phase voltages (paper 000 eq. 36).
//
//   u_min = min(u_a, u_b, u_c);  w_x = sat(u_x - u_min)   (x = a, b, c)
//   The differences are exact and >= 0; they saturate to 2^(V_W-1) - 1 only if the inputs
//   span more than that (sat pulse).  Bit-exact model: gen/empc/rtlmodel/min_sub.py.
// Ports:
//   start              1-cycle request; u_a, u_b, u_c sampled in that cycle; ignored while busy
//   u_a, u_b, u_c      signed V_W-bit phase voltages, Q.4 in PWM ticks (from inv_clarke)
//   busy               high from the cycle after start up to the cycle before done
//   done               1-cycle pulse: w_a, w_b, w_c, sat updated (held until the next done)
//   w_a, w_b, w_c      signed V_W-bit, 0 .. 2^(V_W-1)-1, Q.4 in PWM ticks
//   sat                1-cycle pulse with done if any output saturated
// Parameters: V_W (default from empc_formats.vh).
// Latency: done is high 3 cycles after the start cycle (latch, minimum, subtract).
// Resources: no DSP; two comparators and three subtractors.
// Reset: outputs 0, not busy.
`default_nettype none
`include "empc_formats.vh"
module min_sub #(
    parameter integer V_W = `EMPC_V_W
) (
    input  wire                  clk,
    input  wire                  rst,
    input  wire                  start,
    input  wire signed [V_W-1:0] u_a,
    input  wire signed [V_W-1:0] u_b,
    input  wire signed [V_W-1:0] u_c,
    output reg                   busy,
    output reg                   done,
    output reg  signed [V_W-1:0] w_a,
    output reg  signed [V_W-1:0] w_b,
    output reg  signed [V_W-1:0] w_c,
    output reg                   sat
);
    localparam signed [V_W-1:0] YMAX = {1'b0, {(V_W-1){1'b1}}};

    reg signed [V_W-1:0] r_a, r_b, r_c, m;
    reg                  s1, s2;

    wire signed [V_W-1:0] m_ab = (r_a < r_b) ? r_a : r_b;
    wire signed [V_W-1:0] m_3  = (m_ab < r_c) ? m_ab : r_c;
    wire signed [V_W:0]   d_a  = {r_a[V_W-1], r_a} - {m[V_W-1], m};
    wire signed [V_W:0]   d_b  = {r_b[V_W-1], r_b} - {m[V_W-1], m};
    wire signed [V_W:0]   d_c  = {r_c[V_W-1], r_c} - {m[V_W-1], m};
    // d_x = u_x - min >= 0 and < 2^V_W, so d_x > YMAX iff bit V_W-1 is set
    wire                  h_a  = d_a[V_W-1], h_b = d_b[V_W-1], h_c = d_c[V_W-1];

    always @(posedge clk) begin
        if (rst) begin
            r_a <= {V_W{1'b0}}; r_b <= {V_W{1'b0}}; r_c <= {V_W{1'b0}}; m <= {V_W{1'b0}};
            s1 <= 1'b0; s2 <= 1'b0; busy <= 1'b0;
            w_a <= {V_W{1'b0}}; w_b <= {V_W{1'b0}}; w_c <= {V_W{1'b0}};
            done <= 1'b0; sat <= 1'b0;
        end else begin
            done <= 1'b0;
            sat  <= 1'b0;
            s1   <= start && !busy;
            s2   <= s1;
            if (start && !busy) begin
                r_a <= u_a; r_b <= u_b; r_c <= u_c;
                busy <= 1'b1;
            end
            if (s1) m <= m_3;
            if (s2) begin
                w_a  <= h_a ? YMAX : d_a[V_W-1:0];
                w_b  <= h_b ? YMAX : d_b[V_W-1:0];
                w_c  <= h_c ? YMAX : d_c[V_W-1:0];
                sat  <= h_a | h_b | h_c;
                done <= 1'b1;
                busy <= 1'b0;
            end
        end
    end
endmodule
`default_nettype wire
