// ref_gen: reference generator (paper 000 sec. V-A): time-parameterised
// polynomial segments evaluated once per control period by exact integer
// forward differences (no multipliers).
//
// 16 segment slots, written by the CPU (the register file gathers SEG_LEN,
// SEG_R0_LO/HI, SEG_D1_LO/HI, SEG_D2 and stores them with SEG_FLAGS):
//   len   [31:0]  control periods (0 = the segment never ends)
//   r0    [63:0]  start value, Q.32 of the output unit (32 integer + 32 fraction bits)
//   d1    [63:0]  first forward difference per period, Q.32
//   d2    [31:0]  signed second forward difference per period, Q.32
//   relative      start from the current value instead of r0
//   last          hold at the end of this segment (else go on with slot + 1 mod 16)
// State: head (= w_{k+N}), d1, d2, remaining, and the active segment's
// "ends" (len != 0), "last" and slot number.  Per `advance`:
//   h1 = head + d1; d1' = d1 + sext(d2); remaining' = remaining - 1 (if the segment ends)
//   - start pending (or `start` in this clock): load slot start_slot
//   - else remaining' == 0 and last: hold: head = h1, d1 = d2 = 0, no further end
//   - else remaining' == 0: load slot (slot + 1) mod 16
//   - else head = h1, d1 = d1', remaining = remaining'
//   load(s): head = relative[s] ? h1 : r0[s]; d1, d2, remaining = d1[s], d2[s], len[s]
// A segment of length L that is followed by an absolute one therefore shows
// r0, r0+d1, ... for exactly L periods; the next (relative) segment starts
// from the exact value r(L) = r0 + L d1 + L(L-1)/2 d2.
// `sync` sets head to sync_value with zero differences and hold; the delay
// line is then refilled by N shifts of the synced head in the N clocks after
// the sync (no data multiplexer on the 64*N delay-line flops), so w_k..w_{k+N}
// all equal sync_value N clocks after the sync.  An advance in the clock of a
// sync or during the fill is deferred and executed in the clock after the
// fill (so it acts on the synced state, exactly as if it came after the sync);
// a pending start survives a sync.  `start` in the same clock as an executed
// advance is taken by it; otherwise it stays pending until the next advance.
// `seg_we` in the same clock as a load of that slot: the load sees the old
// contents.
// Output: an N+1 deep delay line w_k .. w_{k+N} (w_{k+N} = head), flattened
// w[64*j +: 64] = w_{k+j}, updated by each advance and valid in the clock after.
// Arithmetic is modular 2^64 (no saturation): for a position unit (encoder
// counts) the integer part wraps modulo 2^32 like the encoder counter, by
// design, and consumers take differences modulo 2^32 of the integer part; for
// a speed unit (counts per Ts) the CPU must keep the profile within +-2^31
// counts/Ts (the generator does not saturate).
//
// Ports:
//   clk, rst                  clock, synchronous active-high reset
//   seg_we, seg_addr[3:0]     store {seg_len, seg_r0, seg_d1, seg_d2, seg_relative, seg_last} into slot seg_addr
//   start, start_slot[3:0]    begin the profile at start_slot at the next advance
//   sync, sync_value[63:0]    set all outputs to sync_value (within N clocks), zero differences, hold
//   advance                   pulse once per control period
//   w[(N+1)*64-1:0]           w_k .. w_{k+N} (Q.32, modular)
// Parameters:
//   N                         prediction horizon (delay line N+1 deep), >= 1
// Latency: 1 clock from advance to w (up to N+1 clocks if the advance came in
//   the clock of a sync or during the following N-clock fill); head 1 clock and
//   the whole delay line N clocks after sync.  Consumers (ctrl_seq) read w
//   microseconds after the advance (after the ADC conversion).
// Reset: head, delay line, differences 0, hold, no start/advance pending, slot 0.
//   The slot memory is not reset (LUT RAM): it is 0 after configuration
//   and keeps its contents over rst.
// Resources (Yosys xc6s, N = 4): slot memory 16 x 194 bit distributed RAM
//   (33 RAM32M = 132 SLICEM LUTs), ~460 flip-flops, ~400 logic LUTs (two
//   64-bit adders, one 32-bit decrementer, the head and difference muxes);
//   no DSP, no BRAM.
`default_nettype none
`include "empc_formats.vh"
module ref_gen #(
    parameter integer N = `EMPC_N
) (
    input  wire                clk,
    input  wire                rst,
    input  wire                seg_we,
    input  wire [3:0]          seg_addr,
    input  wire [31:0]         seg_len,
    input  wire [63:0]         seg_r0,
    input  wire [63:0]         seg_d1,
    input  wire [31:0]         seg_d2,
    input  wire                seg_relative,
    input  wire                seg_last,
    input  wire                start,
    input  wire [3:0]          start_slot,
    input  wire                sync,
    input  wire [63:0]         sync_value,
    input  wire                advance,
    output wire [(N+1)*64-1:0] w
);
    localparam integer NSLOT = 16;
    localparam integer SLW = 32 + 64 + 64 + 32 + 2;     // slot word width

    // ---------------- slot memory (distributed RAM, async read) ----------------
    reg [SLW-1:0] mem [0:NSLOT-1];
    integer mi;
    initial begin
        for (mi = 0; mi < NSLOT; mi = mi + 1) mem[mi] = {SLW{1'b0}};
    end
    always @(posedge clk) begin
        if (seg_we)
            mem[seg_addr] <= {seg_last, seg_relative, seg_d2, seg_d1, seg_r0, seg_len};
    end

    // ---------------- generator state ----------------
    localparam integer FW = $clog2(N + 1);
    localparam [FW-1:0] FILL_N = N[FW-1:0];
    reg  [63:0] head;
    reg  [63:0] d1;
    reg  [31:0] d2;
    reg  [31:0] rem;
    reg         ends;           // active segment has len != 0
    reg         last_r;         // active segment is the last one
    reg  [3:0]  slot;
    reg         pend;
    reg  [3:0]  pend_slot;
    reg  [FW-1:0] fill;         // delay-line shifts left after a sync
    reg         adv_pend;       // advance deferred by a sync fill
    reg  [63:0] dl [0:N-1];     // w_k .. w_{k+N-1}

    wire        filling  = (fill != {FW{1'b0}});
    wire        adv      = (advance || adv_pend) && !filling && !sync;   // executed advance
    wire        shift    = (adv || filling) && !sync;

    wire [63:0] h1       = head + d1;
    wire [63:0] d1n      = d1 + {{32{d2[31]}}, d2};
    wire        seg_end  = ends && (rem == 32'd1);
    wire        do_start = start || pend;
    wire [3:0]  ld_slot  = start ? start_slot : pend ? pend_slot : slot + 4'd1;
    wire        do_load  = do_start || (seg_end && !last_r);
    wire        do_hold  = !do_start && seg_end && last_r;
    wire        zero_dif = rst || sync || (adv && do_hold);  // differences -> 0 (FF reset pins)

    wire [SLW-1:0] rd    = mem[ld_slot];
    wire [31:0] rd_len   = rd[31:0];
    wire [63:0] rd_r0    = rd[95:32];
    wire [63:0] rd_d1    = rd[159:96];
    wire [31:0] rd_d2    = rd[191:160];
    wire        rd_rel   = rd[192];
    wire        rd_last  = rd[193];

    wire [63:0] head_next = (do_load && !rd_rel) ? rd_r0 : h1;

    // delay line: shift only (clock enable), no data mux: a sync refills it
    // by N shifts of the synced head
    integer j;
    always @(posedge clk) begin
        if (rst) begin
            for (j = 0; j < N; j = j + 1) dl[j] <= 64'd0;
        end else if (shift) begin
            for (j = 0; j < N - 1; j = j + 1) dl[j] <= dl[j+1];
            dl[N-1] <= head;
        end
    end

    always @(posedge clk) begin
        if (rst) begin
            head <= 64'd0;
            fill <= {FW{1'b0}};
            adv_pend <= 1'b0;
        end else if (sync) begin
            head <= sync_value;
            fill <= FILL_N;
            adv_pend <= adv_pend || advance;
        end else begin
            if (filling)
                fill <= fill - {{(FW-1){1'b0}}, 1'b1};
            if (adv) begin
                head <= head_next;
                adv_pend <= 1'b0;
            end else if (advance) begin
                adv_pend <= 1'b1;
            end
        end
    end

    always @(posedge clk) begin
        if (zero_dif) begin
            d1 <= 64'd0;
            d2 <= 32'd0;
            rem <= 32'd0;
            ends <= 1'b0;
        end else if (adv) begin
            if (do_load) begin
                d1 <= rd_d1;
                d2 <= rd_d2;
                rem <= rd_len;
                ends <= (rd_len != 32'd0);
            end else begin
                d1 <= d1n;
                if (ends) rem <= rem - 32'd1;
            end
        end
    end

    always @(posedge clk) begin
        if (rst || sync) begin
            last_r <= 1'b0;
        end else if (adv && do_load) begin
            last_r <= rd_last;
        end
    end

    always @(posedge clk) begin
        if (rst) begin
            slot <= 4'd0;
            pend <= 1'b0;
            pend_slot <= 4'd0;
        end else if (adv) begin
            pend <= 1'b0;
            if (do_load) slot <= ld_slot;
        end else if (start) begin
            pend <= 1'b1;
            pend_slot <= start_slot;
        end
    end

    genvar g;
    generate
        for (g = 0; g < N; g = g + 1) begin : g_w
            assign w[g*64 +: 64] = dl[g];
        end
    endgenerate
    assign w[N*64 +: 64] = head;

`ifndef SYNTHESIS
    initial begin
        if (N < 1) $display("ERROR: ref_gen N=%0d must be >= 1", N);
    end
`endif
endmodule
`default_nettype wire
