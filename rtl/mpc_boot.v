// mpc_boot: the MPC core's registered coefficient write port: boot image after reset, then the
// CPU; and the image checker that validates every upload (boot stream or CPU) as it is written.
//
// After reset the boot image (BOOT_FILE, 32-bit words in the layout of gen/empc/image.py,
// $readmemh) is streamed from a ROM, words 0..USED-1 one per clock, through the write port
// (we / addr / data), once into every axis (NAXES passes, `wax` = 0 .. NAXES-1; a pass takes
// DEPTH clocks, the counter runs through the unused top quarter between passes); then `ready`
// rises and stays high and the port carries the CPU's requests (cfg_we / cfg_axis / cfg_addr /
// cfg_wdata), registered: a request appears one clock later.
// Structure (no fabric multiplexer on the 32 data bits): the ROM's block RAM port runs in
// WRITE_FIRST mode; once ready it writes the CPU word to a scratch word above USED every
// clock, so its output register (`data`) shows the CPU word.  The write address register
// is the boot counter while streaming ({ready ? cfg_addr : addr} + !ready on one carry chain).
// The ROM words 0..USED-1 are never written: every reset streams the original image.
//
// Image checker (image.check of the model, gen/empc/rtlmodel/mpc_core.py Banks): an upload
// is the words 0..USED-1 of one axis written in ascending order, each once, starting at word 0;
// a write of word 0 (re)starts it (one upload at a time: the checker is shared by the axes).
// For every word in the port:
//   word 0     restart: acc = the word (its sync reset one clock ahead), bad = (word != MAGIC)
//   other      in sequence iff addr == previous addr + 1 and the same axis as the previous
//              word; bad |= out of sequence or a wrong
//              header word: CFG (layout == LAYOUT, reserved bits 15 and 7 0, algorithm 1 or 2,
//              any control period [23:16]: not the checker's, mpc_core compares it with the axis's,
//              N == the build's N, ncols <= 64), USED (== USED), FMT (== the build's format
//              fingerprint EMPC_IMG_FMT_ID); acc += word (csum word: acc -= word)
//   upl_ok[wax] <= (this word is USED-1, in sequence, !bad, acc after it == 0): the words since
//   the last word 0 are exactly one complete image of axis wax with a valid checksum for this
//   build; the other axes' upl_ok hold.
//   The header compares run one clock behind the port, on a copy of the header word (hq,
//   loaded only at header words): the block RAM output `data` then feeds only the write
//   port and the accumulator, so the mapper cannot share the coefficient clamp's wide tests
//   with the compares (it did: 9 LUT levels, 93 MHz).  A compare result arriving with a
//   word 0 belongs to the abandoned image and is dropped; the header words are words 0..11,
//   so every result is in `bad` long before the last word.
//   Any later write to that axis (another word, a rewrite) clears its upl_ok; so does
//   ok_clr[a] (the core swapped the upload in: the inactive bank is the old one again) and,
//   for every axis, the end of the boot stream.
// Ports: cfg_we, cfg_axis, cfg_addr, cfg_wdata (CPU, used when ready); ok_clr[NAXES] (pulses);
//   we, wax, addr, data (write port); ready; ok (boot image valid: latched at the end of the
//   boot stream, the check of the last pass); upl_ok[NAXES] (a complete valid image was written
//   into that axis since its last ok_clr, nothing after it); ok_next (the value ok takes at the
//   next edge unless rst: lets the core register its img_ok without a gate after the flip-flops).
// Parameters: BOOT_FILE, DEPTH (ROM words, EMPC_IMG_DEPTH = 1024), USED (words streamed,
//   EMPC_IMG_USED, <= 3/4 DEPTH: the CPU words go to the top quarter), N (the core's horizon),
//   NAXES (axes, 1..8), AXW (axis index width, >= 1).
// Latency: the stream writes word k of axis a in clock a DEPTH + k + 2 after rst is released;
//   ready rises (NAXES - 1) DEPTH + USED + 3 clock cycles after rst is released (771 for one
//   axis, 3843 for four), ok one clock earlier; upl_ok: 1 clock after the last word is in the
//   port (2 after its request).
// Reset: restarts the stream; we, ready, ok and upl_ok clear (addr, data: don't care while we = 0).
`default_nettype none
`include "empc_formats.vh"
module mpc_boot #(
    parameter BOOT_FILE = "coef_boot.hex",
    parameter integer DEPTH = `EMPC_IMG_DEPTH,
    parameter integer USED = `EMPC_IMG_USED,
    parameter integer N = `EMPC_N,
    parameter integer NAXES = 1,
    parameter integer AXW = 1
) (
    input  wire             clk,
    input  wire             rst,
    input  wire             cfg_we,
    input  wire [AXW-1:0]   cfg_axis,
    input  wire [9:0]       cfg_addr,
    input  wire [31:0]      cfg_wdata,
    input  wire [NAXES-1:0] ok_clr,
    output reg              we,
    output reg  [AXW-1:0]   wax,
    output reg  [9:0]       addr,
    output reg  [31:0]      data,
    output reg              ready,
    output reg              ok,
    output wire             ok_next,
    output reg  [NAXES-1:0] upl_ok
);
    localparam [9:0] A_CSUM  = `EMPC_IMG_A_CSUM;
    localparam [9:0] LAST    = USED[9:0] - 10'd1;
    localparam [9:0] A_RST   = 10'd0 - 10'd2;          // addr after reset: word 0 is written in clock 2
    localparam [31:0] MAGIC  = `EMPC_IMG_MAGIC;
    localparam [9:0]  A_CFG  = `EMPC_IMG_A_CFG;
    localparam [9:0]  A_USED = `EMPC_IMG_A_USED;
    localparam [9:0]  A_FMT  = `EMPC_IMG_A_FMT;
    localparam [31:0] USED_W = USED;
    localparam [31:0] FMT_ID = `EMPC_IMG_FMT_ID;
    localparam [7:0]  LAYOUT = `EMPC_IMG_LAYOUT;
    localparam [31:0] N_W    = N;
    localparam [6:0]  MAXC   = `EMPC_MAX_COLS;
    localparam integer   AX_LASTI = NAXES - 1;
    localparam [AXW-1:0] AX_LAST = AX_LASTI[AXW-1:0];
    generate if (DEPTH != 1024 || USED > DEPTH / 4 * 3 || USED < 12 || NAXES < 1 || NAXES > (1 << AXW))
    begin : g_bad_params
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

    // checker: acc = sum of the words except the checksum word, minus the checksum word
    reg  [31:0] acc;
    reg         bad;                                  // since the last word 0: out of sequence / wrong header
    reg         last;                                 // the clock after the last boot word
    reg  [9:0]  nexp;                                 // previous word's address + 1
    reg  [AXW-1:0] nax;                               // previous word's axis
    reg  [AXW-1:0] bax;                               // boot pass (axis)
    wire        bnext = we && boot && (addr == LAST) && (wax != AX_LAST);   // a pass ends, another follows
    wire [AXW-1:0] bax_n = (NAXES == 1) ? {AXW{1'b0}} : bax + {{(AXW-1){1'b0}}, bnext};
    reg         csw, w0, wcfg, wused, wfmt;           // decodes of the port address (registered: a_next)
    reg  [31:0] hq;                                   // the last header word (compared one clock later)
    reg         h0, hcfg, hused, hfmt;                // which header word hq holds (pulses, one clock)
    // acc + (data ^ csw) + csw, the carry-in as an extra LSB (keeps acc on the carry chain's DI inputs)
    wire [32:0] acc_nx = {acc, 1'b1} + {data ^ {32{csw}}, csw};
    wire [31:0] acc_n = acc_nx[32:1];
    wire        we_n = ready ? cfg_we : (a_next < USED[9:0]);
    // header words: one comparator against the constant of the word (MAGIC, USED or the format id)
    wire [31:0] hexp = h0 ? MAGIC : hused ? USED_W : FMT_ID;
    wire        cfg_bad = (hq[31:24] != LAYOUT) || hq[15] || (hq[14:13] == 2'd0) ||
                          (hq[14:13] == 2'd3) || (hq[11:8] != N_W[3:0]) || hq[7] || (hq[6:0] > MAXC);
    wire        hdr_bad = ((h0 || hused || hfmt) && (hq != hexp)) || (hcfg && cfg_bad);
    always @(posedge clk) begin
        if (we && (w0 || wcfg || wused || wfmt)) hq <= data;
        h0    <= we && w0 && !rst;
        hcfg  <= we && wcfg && !rst;
        hused <= we && wused && !rst;
        hfmt  <= we && wfmt && !rst;
    end
    wire        in_seq = (addr == nexp) && (wax == nax);
    wire        upl_n  = !w0 && in_seq && !bad && (addr == LAST) && (acc_n == 32'd0);
    always @(posedge clk) begin
        if (rst || (we_n && a_next == 10'd0)) acc <= 32'd0;    // restart: cleared before word 0
        else if (we)                          acc <= acc_n;
    end
    assign ok_next = last ? upl_ok[NAXES-1] : ok;
    integer ai;
    always @(posedge clk) begin
        if (rst) begin
            addr  <= A_RST;
            we    <= 1'b0;
            ready <= 1'b0;
            boot  <= 1'b1;
            ok    <= 1'b0;
            upl_ok <= {NAXES{1'b0}};
            bad   <= 1'b1;
            nexp  <= 10'd0;
            nax   <= {AXW{1'b0}};
            bax   <= {AXW{1'b0}};
            wax   <= {AXW{1'b0}};
            last  <= 1'b0;
            csw   <= 1'b0;
            w0    <= 1'b0;
            wcfg  <= 1'b0;
            wused <= 1'b0;
            wfmt  <= 1'b0;
        end else begin
            addr  <= a_next;
            bax   <= bax_n;
            wax   <= ready ? cfg_axis : bax_n;
            csw   <= (a_next == A_CSUM);
            w0    <= (a_next == 10'd0);
            wcfg  <= (a_next == A_CFG);
            wused <= (a_next == A_USED);
            wfmt  <= (a_next == A_FMT);
            we    <= we_n;
            last  <= we && boot && (addr == LAST) && (wax == AX_LAST);
            if (last) begin                           // the clock after the last boot word
                ready <= 1'b1;
                boot  <= 1'b0;
                ok    <= upl_ok[NAXES-1];
            end
            if (we) begin
                nexp   <= addr + 10'd1;
                nax    <= wax;
                bad    <= w0 ? 1'b0 : (bad || hdr_bad || !in_seq);
            end else if (hdr_bad) begin
                bad <= 1'b1;                          // the compare of the word before (no word now)
            end
            for (ai = 0; ai < NAXES; ai = ai + 1) begin
                if (we && wax == ai[AXW-1:0]) upl_ok[ai] <= upl_n;
                else if (last || ok_clr[ai])  upl_ok[ai] <= 1'b0;
            end
        end
    end

    wire unused_ok = &{1'b0, acc_nx[0]};
endmodule
`default_nettype wire
