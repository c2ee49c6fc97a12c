// mpc_boot: streams the boot coefficient image into the MPC core's write port after reset.
//
// The image (BOOT_FILE, 32-bit words in the layout of gen/empc/image.py, $readmemh)
// sits in a ROM; after reset words 0..USED-1 are written one per clock through the
// same write path the CPU uses (we / addr / data), then `done` rises and stays high.
// While streaming, the sum of all words except the checksum word is formed; `ok` is
// 1 when done and the magic word and the checksum (image.checksum) match.
// Ports: we, addr, data (write port), done, ok.
// Parameters: BOOT_FILE, DEPTH (ROM words, EMPC_IMG_DEPTH), USED (words streamed, EMPC_IMG_USED).
// Latency: done rises USED + 2 clock cycles after rst is released (770 for USED = 768).
// Reset: restarts the stream; done, ok and we clear.
`default_nettype none
`include "empc_formats.vh"
module mpc_boot #(
    parameter BOOT_FILE = "coef_boot.hex",
    parameter integer DEPTH = `EMPC_IMG_DEPTH,
    parameter integer USED = `EMPC_IMG_USED
) (
    input  wire        clk,
    input  wire        rst,
    output reg         we,
    output reg  [9:0]  addr,
    output reg  [31:0] data,
    output reg         done,
    output reg         ok
);
    localparam [9:0] A_MAGIC = 10'd0;
    localparam [9:0] A_CSUM  = `EMPC_IMG_A_CSUM;
    localparam [9:0] LAST    = USED[9:0] - 10'd1;
    localparam [31:0] MAGIC  = `EMPC_IMG_MAGIC;

    reg [31:0] rom [0:DEPTH-1];
    initial $readmemh(BOOT_FILE, rom);

    reg [9:0]  cnt;
    reg        run;
    reg [31:0] sum;
    reg [31:0] csum;
    reg        magic_ok;
    always @(posedge clk) begin
        if (rst) begin
            cnt  <= 10'd0;
            run  <= 1'b1;
            we   <= 1'b0;
            addr <= 10'd0;
            data <= 32'd0;
            done <= 1'b0;
            ok   <= 1'b0;
            sum  <= 32'd0;
            csum <= 32'd0;
            magic_ok <= 1'b0;
        end else begin
            data <= rom[cnt];
            addr <= cnt;
            we   <= run;
            if (run) begin
                cnt <= cnt + 10'd1;
                if (cnt == LAST) run <= 1'b0;
            end
            if (we) begin
                if (addr == A_CSUM) csum <= data;
                else sum <= sum + data;
                if (addr == A_MAGIC) magic_ok <= (data == MAGIC);
            end
            if (!run && !we && !done) begin
                done <= 1'b1;
                ok   <= magic_ok && (sum == csum);
            end
        end
    end
endmodule
`default_nettype wire
