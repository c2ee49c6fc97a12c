// mpc_boot: the MPC core's registered coefficient write port: boot image after reset, then the CPU.
//
// After reset the boot image (BOOT_FILE, 32-bit words in the layout of gen/empc/image.py,
// $readmemh) is streamed from a ROM, words 0..USED-1 one per clock, through the write port
// (we / addr / data); then `ready` rises and stays high and the port carries the CPU's
// requests (cfg_we / cfg_addr / cfg_wdata), registered: a request appears one clock later.
// While streaming, the sum of all words except the checksum word is formed; `ok` is 1
// when the magic word and the checksum (image.checksum) match (valid one clock before ready).
// Structure (no fabric multiplexer on the 32 data bits): the ROM's block RAM port runs in
// WRITE_FIRST mode; once ready it writes the CPU word to a scratch word above USED every
// clock, so its output register (`data`) shows the CPU word.  The write address register
// is the boot counter while streaming ({ready ? cfg_addr : addr} + !ready on one carry chain).
// The ROM words 0..USED-1 are never written: every reset streams the original image.
// Ports: cfg_we, cfg_addr, cfg_wdata (CPU, used when ready); we, addr, data (write port);
//   ready, ok.
// Parameters: BOOT_FILE, DEPTH (ROM words, EMPC_IMG_DEPTH = 1024), USED (words streamed,
//   EMPC_IMG_USED, <= 3/4 DEPTH: the CPU words go to the top quarter).
// Latency: the stream writes word k in clock k + 2 after rst is released; ready rises
//   USED + 3 clock cycles after rst is released (771 for USED = 768), ok one clock earlier.
// Reset: restarts the stream; we, ready and ok clear (addr, data: don't care while we = 0).
`default_nettype none
`include "empc_formats.vh"
module mpc_boot #(
    parameter BOOT_FILE = "coef_boot.hex",
    parameter integer DEPTH = `EMPC_IMG_DEPTH,
    parameter integer USED = `EMPC_IMG_USED
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        cfg_we,
    input  wire [9:0]  cfg_addr,
    input  wire [31:0] cfg_wdata,
    output reg         we,
    output reg  [9:0]  addr,
    output reg  [31:0] data,
    output reg         ready,
    output reg         ok
);
    localparam [9:0] A_CSUM  = `EMPC_IMG_A_CSUM;
    localparam [9:0] LAST    = USED[9:0] - 10'd1;
    localparam [9:0] A_RST   = 10'd0 - 10'd2;          // addr after reset: word 0 is written in clock 2
    localparam [31:0] MAGIC  = `EMPC_IMG_MAGIC;
    generate if (DEPTH != 1024 || USED > DEPTH / 4 * 3 || USED < 12) begin : g_bad_params
        mpc_boot_unsupported_parameters u_error ();      // no such module: elaboration stops here
    end endgenerate

    reg [31:0] rom [0:DEPTH-1];
    initial $readmemh(BOOT_FILE, rom);

    reg        boot;                                  // = !ready (its own flip-flop: no inverter)
    // next write address: the CPU's (ready) or the boot counter
    wire [9:0] a_sel  = ready ? cfg_addr : addr;
    wire [9:0] a_next = a_sel + {9'd0, boot};
    // ROM port address: the next boot word, or (ready) a scratch word in the top quarter
    wire [9:0] ra     = {a_next[9:8] | {2{ready}}, a_next[7:0]};

    always @(posedge clk) begin
        if (ready) rom[ra] <= cfg_wdata;
        if (rst) data <= 32'd0;
        else     data <= ready ? cfg_wdata : rom[ra];  // WRITE_FIRST: the CPU word once ready
    end

    // checksum: acc = sum of the words except the checksum word, minus the checksum word
    reg  [31:0] acc;
    reg         magic_ok, first, last;
    reg         csw;                                  // addr == A_CSUM (registered: one shared net)
    // acc + (data ^ csw) + csw, the carry-in as an extra LSB (keeps acc on the carry chain's DI inputs)
    wire [32:0] acc_nx = {acc, 1'b1} + {data ^ {32{csw}}, csw};
    wire [31:0] acc_n = acc_nx[32:1];
    wire        bw   = we && boot;                    // boot word in the write port
    always @(posedge clk) begin
        if (rst) begin
            addr  <= A_RST;
            we    <= 1'b0;
            ready <= 1'b0;
            boot  <= 1'b1;
            ok    <= 1'b0;
            acc   <= 32'd0;
            magic_ok <= 1'b0;
            first <= 1'b1;
            last  <= 1'b0;
            csw   <= 1'b0;
        end else begin
            addr  <= a_next;
            csw   <= (a_next == A_CSUM);
            we    <= ready ? cfg_we : (a_next < USED[9:0]);
            last  <= bw && (addr == LAST);
            if (last) begin                           // the clock after the last boot word
                ready <= 1'b1;
                boot  <= 1'b0;
            end
            if (bw) begin
                acc   <= acc_n;
                first <= 1'b0;
                if (first) magic_ok <= (data == MAGIC);          // the magic is word 0
                if (addr == LAST) ok <= magic_ok && (acc_n == 32'd0);
            end
        end
    end

    wire unused_ok = &{1'b0, acc_nx[0]};
endmodule
`default_nettype wire
