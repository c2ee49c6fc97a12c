// sync_2ff: two-flip-flop synchroniser for asynchronous single-bit inputs.
//
// Every signal that enters the fabric clock domain asynchronously (encoder
// A/B/index, HALL, SPI MISO, PWM sync, CPU bus strobes) passes through this
// module, so CDC points are easy to find and constrain (TIG on `d`).
// Ports: d (async, WIDTH bits, each bit independent), q (synchronous).
// Latency: STAGES clock cycles. Reset: q and the chain load RESET_VALUE (also their
// power-up value: an instance with rst tied to 0 starts from it).
`default_nettype none
module sync_2ff #(
    parameter integer WIDTH = 1,
    parameter integer STAGES = 2,
    parameter [WIDTH-1:0] RESET_VALUE = {WIDTH{1'b0}}
) (
    input  wire             clk,
    input  wire             rst,
    input  wire [WIDTH-1:0] d,
    output wire [WIDTH-1:0] q
);
    (* ASYNC_REG = "TRUE" *) reg [WIDTH-1:0] stage [0:STAGES-1];
    integer i;
    initial for (i = 0; i < STAGES; i = i + 1) stage[i] = RESET_VALUE;   // FPGA INIT (rst may be tied 0)
    always @(posedge clk) begin
        if (rst) begin
            for (i = 0; i < STAGES; i = i + 1) stage[i] <= RESET_VALUE;
        end else begin
            stage[0] <= d;
            for (i = 1; i < STAGES; i = i + 1) stage[i] <= stage[i-1];
        end
    end
    assign q = stage[STAGES-1];
endmodule
`default_nettype wire
