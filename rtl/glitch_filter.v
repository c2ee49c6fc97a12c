// glitch_filter: per-bit digital glitch filter (debouncer) for synchronised inputs.
//
// Each bit i keeps a counter.  While d[i] equals q[i] the counter is held at 0;
// while d[i] differs from q[i] it counts the consecutive differing samples, and
// on the L-th such sample q[i] takes d[i] (counter back to 0).  So q[i] changes
// only after d[i] has been stable at the new value for L clocks: a pulse of
// L-1 clocks never reaches q, a pulse of L clocks does (and then lasts L clocks).
//   L = (len == 0) ? FILTER_LEN : len       (run-time register, 0 = parameter)
// L = 1 is a plain one-register delay.  The input must already be synchronous
// (put sync_2ff in front of it).
//
// Ports:
//   clk, rst     clock, synchronous active-high reset
//   load         q <= d and all counters cleared (start-up / re-initialisation,
//                so that the first real level is not seen as an edge)
//   len          run-time filter length in clocks, 0 selects FILTER_LEN
//   d            synchronous input, WIDTH independent bits
//   q            filtered output (registered)
// Parameters:
//   WIDTH        number of independent bits
//   FILTER_LEN   default filter length in clocks (1 .. 2**LEN_W-1)
//   LEN_W        width of len and of each counter
//   RESET_VALUE  q after reset
// Latency: L clock cycles from a change of d to the change of q.
// Reset: q = RESET_VALUE, counters 0.
// Resources: WIDTH * (LEN_W + 1) flip-flops, no DSP/BRAM.
`default_nettype none
module glitch_filter #(
    parameter integer WIDTH = 1,
    parameter integer FILTER_LEN = 4,
    parameter integer LEN_W = 8,
    parameter [WIDTH-1:0] RESET_VALUE = {WIDTH{1'b0}}
) (
    input  wire             clk,
    input  wire             rst,
    input  wire             load,
    input  wire [LEN_W-1:0] len,
    input  wire [WIDTH-1:0] d,
    output wire [WIDTH-1:0] q
);
    localparam [LEN_W-1:0] DEF_LEN = FILTER_LEN[LEN_W-1:0];

    wire [LEN_W-1:0] len_eff = (len == {LEN_W{1'b0}}) ? DEF_LEN : len;

    genvar i;
    generate
        for (i = 0; i < WIDTH; i = i + 1) begin : g_bit
            reg              qr;
            reg  [LEN_W-1:0] cnt;
            wire [LEN_W:0]   cnt_inc = {1'b0, cnt} + {{LEN_W{1'b0}}, 1'b1};
            always @(posedge clk) begin
                if (rst) begin
                    qr   <= RESET_VALUE[i];
                    cnt  <= {LEN_W{1'b0}};
                end else if (load) begin
                    qr   <= d[i];
                    cnt  <= {LEN_W{1'b0}};
                end else if (d[i] == qr) begin
                    cnt  <= {LEN_W{1'b0}};
                end else if (cnt_inc >= {1'b0, len_eff}) begin
                    qr   <= d[i];
                    cnt  <= {LEN_W{1'b0}};
                end else begin
                    cnt  <= cnt_inc[LEN_W-1:0];
                end
            end
            assign q[i] = qr;
        end
    endgenerate

`ifndef SYNTHESIS
    initial begin
        if (FILTER_LEN < 1 || FILTER_LEN >= (1 << LEN_W))
            $display("ERROR: glitch_filter FILTER_LEN=%0d out of range 1..%0d", FILTER_LEN, (1 << LEN_W) - 1);
    end
`endif
endmodule
`default_nettype wire
