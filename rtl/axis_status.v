// axis_status: the status words and event counters of NAXES axes, in one block RAM ({axis, word}:
// 64 x 32 per axis; NAXES = 4: 256 x 32, one RAMB16).
//
// Words (register offsets, empc_regs.vh): the status words SPEED, I_D, I_Q, U_D, U_Q, REF, written
// whole by the sequencer (mx_seq), and the counters SAT_OPERAND .. CNT_OVERRUN (13 words from
// SAT_OPERAND on, counter i counts event i), PERIODS and SAT_GOV, which this block counts itself
// (docs/four_axes.md D6: the counter sweep is off the engine, on this block's own port).
//
// Port A: CPU read (priority), the sequencer's word write (st_we: one that meets a CPU read waits
// one clock; the sequencer's program keeps its status writes >= 2 clocks apart and the bus reads at
// most every other clock, so one deferred write is enough; the sequencer holds st_addr / st_wdata
// in the clock after st_we, so the deferred write takes them from the ports), else a sweep write.
// Port B: the sweep's counter read.
// Events, per axis (held in flip-flops from their pulse to the axis's next counting sweep, so SAT_*
// and CNT_OVERRUN count the control periods in which the event happened): core_flags at core_done
// (SAT_OPERAND .. SAT_SIGNAL), front_sat (SAT_FRONT), overrun (CNT_OVERRUN), period (PERIODS), gov
// (SAT_GOV).
// Counting sweep of axis a (sweep[a] pulse: a control period's job of axis a ended): taken unless
// axis a is busy (a sweep of a runs or waits; then the pulse is not taken and its events stay held
// for the next one); a taken pulse moves the events, including this clock's, into axis a's snapshot
// and clears them.  The sweep then reads counter k = 0..14 of axis a on port B, adds its event and
// writes it back on port A when port A is free (saturating at 2^32 - 1: the write is dropped;
// PERIODS wraps): one counter a clock, 16 clocks without CPU traffic.
// Zero sweep: after rst all NW = 64 << clog2(NAXES) words, after cnt_clear[a] axis a's 15 counters
// are written 0 (one a clock when port A is free); the words stay hidden (read 0) from the rst /
// command until that sweep ends: after rst every word, after cnt_clear[a] only axis a's counters.
// A clear of axis a abandons a's counting sweep (running or waiting); a clear during the zero sweep
// after rst holds that sweep one clock (it stays whole and covers the clear).
// One sweep engine for all axes (NAXES > 1): sweeps of different axes queue.  A pulse taken or a
// clear of an axis that the engine is not serving waits (flag per axis); an idle engine starts the
// request (a clear: zero sweep, else the counting sweep) of the first axis after the last one it
// served, round robin, so a queued sweep starts the clock after the previous one ended (17 clocks
// per sweep without CPU traffic) and waits for at most one sweep of each other axis.  A clear of
// the engine's axis restarts the engine as that axis's zero sweep at once.  An axis's counters,
// reads and busy do not depend on the other axes' events, words, pulses or clears except through
// that queue wait (and the port-A clocks the CPU reads and word writes take), so they are the same
// with and without the other axes' traffic as long as its own pulses and clears come after the
// wait (they are a control period apart).
//
// Ports: reg_rd / reg_addr ({axis, offset}) -> rdata, valid the clock after reg_rd, 0 unless a word
// of this block is read (ORed into the axis read data).  st_addr is {axis, word}.  The event, sweep,
// cnt_clear and busy vectors have one bit per axis, core_flags 11 bits per axis.  busy[a]: a sweep
// of axis a runs or waits (every axis during the zero sweep after rst).
// Parameter: NAXES (1..8; 1: the one-axis block, every vector one bit; offsets from empc_regs.vh,
// elaboration stops if the counters are not contiguous below 64).
// Latency: a word written by st_we reads from the next clock on (two clocks if it met a read); a
// counting sweep ends at most 16 + (clocks port A is taken) clocks after its pulse, plus the sweeps
// of other axes ahead of it in the queue.
// Reset: events 0, every word hidden until the zero sweep after rst (NW clocks) has ended.
// Bit-exact, clock by clock, to gen/empc/rtlmodel/axis_status.py.
`default_nettype none
`include "empc_regs.vh"
module axis_status #(
    parameter integer NAXES = 1                         // axes (1..4 in one RAMB16; AXB = clog2(NAXES))
) (
    input  wire        clk,
    input  wire        rst,
    // CPU read port
    input  wire        reg_rd,          // any CPU read (port A arbitration)
    input  wire [7+$clog2(NAXES):0] reg_addr,   // {axis, axis word offset}
    input  wire        cnt_re,          // read of a counter word (the register block's address table)
    input  wire        stat_re,         // read of a status word (the register block's address table)
    output reg  [31:0] rdata,
    input  wire [NAXES-1:0] cnt_clear,  // pulse per axis: zero that axis's counters (CMD.clear_counters)
    // events of the control period, per axis
    input  wire [NAXES-1:0] core_done,
    input  wire [11*NAXES-1:0] core_flags,  // axis a: core_flags[11a +: 11]
    input  wire [NAXES-1:0] front_sat,
    input  wire [NAXES-1:0] overrun,
    input  wire [NAXES-1:0] period,
    input  wire [NAXES-1:0] gov,
    // status words from the sequencer
    input  wire        st_we,
    input  wire [5+$clog2(NAXES):0] st_addr,    // {axis, word}; held (with st_wdata) in the clock after st_we
    input  wire [31:0] st_wdata,
    // counting sweeps
    input  wire [NAXES-1:0] sweep,
    output wire [NAXES-1:0] busy
);
    localparam integer AXB = $clog2(NAXES);             // axis bits of reg_addr / st_addr / the memory address
    localparam integer AXW = (AXB > 0) ? AXB : 1;
    localparam integer AW = 6 + AXB;                    // memory address {axis, word}
    localparam integer NW = 64 << AXB;                  // memory words (the zero sweep after rst: all)
    localparam integer A_CNT0 = `EMPC_A_SAT_OPERAND;    // counter of event i: A_CNT0 + i (i < 13)
    localparam integer NEV = 13;
    localparam integer A_CNT_LAST = A_CNT0 + NEV - 1;
    localparam integer NCNT = NEV + 2;                  // + PERIODS, SAT_GOV
    localparam [5:0]   K_NEV = NEV[5:0];
    localparam integer K_ALL_I = NW - 1;                // last word of the zero sweep after rst
    localparam integer K_CNT_I = NCNT - 1;              // last word of an axis's sweep
    localparam [AW-1:0] K_ALL = K_ALL_I[AW-1:0];
    localparam [AW-1:0] K_CNT = K_CNT_I[AW-1:0];
    localparam [AXW:0]  NAX = NAXES[AXW:0];
    localparam         QUEUE = (NAXES > 1);             // sweeps of other axes can be pending

    generate if (`EMPC_A_CNT_OVERRUN != A_CNT_LAST || `EMPC_A_SAT_FRONT != A_CNT_LAST - 1 || A_CNT_LAST > 63 ||
                 `EMPC_A_PERIODS > 63 || `EMPC_A_SAT_GOV > 63 || `EMPC_A_I_D > 63 || `EMPC_A_REF > 63 ||
                 `EMPC_A_SPEED > 63 || NAXES < 1 || NAXES > 8)
    begin : g_bad_map
        axis_status_unsupported_register_map u_error ();   // no such module: elaboration stops here
    end endgenerate

    // ---------------- events, per axis ----------------
    reg  [NCNT*NAXES-1:0] ev;           // held events of axis a: ev[NCNT*a +: NCNT]
    reg  [16*NAXES-1:0] sq;             // the events a taken sweep pulse of axis a adds: sq[16a +: NCNT]
    reg  [NAXES-1:0] cp, zp;            // a counting / zero sweep of axis a waits for the engine
    reg  [NAXES-1:0] hide_cnt;          // axis a's counters read 0
    reg         hide_st;                // the status words read 0 (until the zero sweep after rst ends)
    reg         act, zact, zall;        // counting sweep / zero sweep running; the zero sweep is of all words
    reg  [AXW-1:0] ax;                  // axis of the running sweep
    reg  [AW-1:0]  k;                   // word of the sweep
    wire [NAXES-1:0] eng_on;            // the engine's sweep is axis a's (or the zero sweep of all words)
    wire [NAXES-1:0] served;            // the idle engine starts axis a's requested sweep now
    wire [NAXES-1:0] on_ax;             // the engine runs a sweep of axis a (or the zero sweep after rst from a)
    wire        idle;
    wire        zrun = zact && zall;                            // the zero sweep after rst
    wire        start;
    wire [AXW-1:0] pick;                // the axis whose request an idle engine starts
    wire [NAXES-1:0] take = sweep & ~busy;
    wire [NCNT*NAXES-1:0] ev_now;       // this clock's events on top of the held ones (what a pulse takes)
    genvar ga;
    generate for (ga = 0; ga < NAXES; ga = ga + 1) begin : g_ax
        wire [NCNT-1:0] evh = ev[NCNT*ga +: NCNT];
        assign ev_now[NCNT*ga +: NCNT] = {gov[ga] | evh[14], period[ga] | evh[13], overrun[ga] | evh[12],
                                          front_sat[ga] | evh[11],
                                          core_done[ga] ? core_flags[11*ga +: 11] : evh[10:0]};
        localparam [AXW-1:0] GA = ga;
        assign eng_on[ga] = (act || zact) && (zall || ax == GA);
        assign served[ga] = start && pick == GA;
        assign on_ax[ga] = !idle && ax == GA;
        always @(posedge clk) begin
            if (rst || take[ga]) ev[NCNT*ga +: NCNT] <= {NCNT{1'b0}};
            else                 ev[NCNT*ga +: NCNT] <= ev_now[NCNT*ga +: NCNT];
            if (take[ga]) sq[16*ga +: 16] <= {1'b0, ev_now[NCNT*ga +: NCNT]};
        end
    end endgenerate
    assign busy = eng_on | cp | zp;
    initial sq = {16*NAXES{1'b0}};

    // address of sweep word k: the counters of axis ax in event order, or (zero sweep after rst) word k
    wire [5:0]  kw = k[5:0];
    wire [5:0]  cnt_a = (kw < K_NEV) ? (A_CNT0[5:0] + kw) : (kw == K_NEV) ? `EMPC_A_PERIODS : `EMPC_A_SAT_GOV;
    wire [AW-1:0] sw_a;
    wire [AW-1:0] b_addr;
    wire [AW-1:0] ra;                   // the CPU read's memory address
    wire [AXW-1:0] r_ax;                // the CPU read's axis
    wire [5:0]  kw1 = kw + 6'd1;
    wire [5:0]  cnt_a1 = (kw1 < K_NEV) ? (A_CNT0[5:0] + kw1) : (kw1 == K_NEV) ? `EMPC_A_PERIODS : `EMPC_A_SAT_GOV;
    wire        go;
    generate if (AXB == 0) begin : g_a1
        assign sw_a = zall ? k : cnt_a;
        // port B reads word k + 1 when the sweep steps now, else word k: both addresses from registers,
        // `go` (behind the CPU read decode, reg_rd) picks one in the last gate
        assign b_addr = go ? cnt_a1 : cnt_a;
        assign ra = reg_addr[5:0];
        assign r_ax = 1'b0;
        assign cnt_ev = sq[k[3:0]];
    end else begin : g_an
        assign sw_a = zall ? k : {ax, cnt_a};
        assign b_addr = {ax, go ? cnt_a1 : cnt_a};
        assign ra = {reg_addr[7+AXB:8], reg_addr[5:0]};
        assign r_ax = reg_addr[7+AXB:8];
        assign cnt_ev = sq[{ax, k[3:0]}];
    end endgenerate
    wire [AW-1:0] k_last = zall ? K_ALL : K_CNT;

    // ---------------- memory ----------------
    (* ram_style = "block" *) reg [31:0] smem [0:NW-1];
    integer si;
    initial begin
        for (si = 0; si < NW; si = si + 1) smem[si] = 32'd0;
    end
    // port A: CPU read, the (deferred) word write, a sweep write; a deferred write takes the held
    // st_addr / st_wdata (no copy here)
    reg         w_def;
    wire        w_now = st_we && !reg_rd;
    wire        w_st = w_def || w_now;
    wire        a_free = !reg_rd && !w_def && !st_we;
    // port B: the counter of word k (q_ok: q is word k's)
    reg  [31:0] q;
    reg         q_ok;
    wire        cnt_ev;                 // the event of counter k of the running sweep's axis
    wire        c_full = &q;
    wire        go_c = act && q_ok && a_free;
    wire        go_z = zact && a_free;
    assign      go   = go_c || go_z;
    wire        sw_wr = go_z || (go_c && !(cnt_ev && c_full && cnt_a != `EMPC_A_PERIODS));
    wire [31:0] sw_d  = go_z ? 32'd0 : q + {31'd0, cnt_ev};
    always @(posedge clk) q <= smem[b_addr];
    wire        r_ok = (NAXES == (1 << AXB)) || ({1'b0, r_ax} < NAX);    // a read of no axis reads 0
    wire        s_rd = r_ok && ((cnt_re && !hide_cnt[r_ax]) || (stat_re && !hide_st));
    wire [AW-1:0] pa = reg_rd ? ra : w_st ? st_addr : sw_a;
    wire        pa_we = !reg_rd && (w_st || (go && sw_wr));
    wire [31:0] pa_d = w_st ? st_wdata : sw_d;
    wire        unused_addr = &{1'b0, reg_addr[7:6]};   // cnt_re / stat_re already decode the page
    always @(posedge clk) begin
        if (pa_we) smem[pa] <= pa_d;
        if (!(reg_rd && s_rd))
            rdata <= 32'd0;
        else
            rdata <= smem[pa];
    end
    always @(posedge clk) w_def <= st_we && reg_rd && !rst;

    // ---------------- sweeps ----------------
    // one engine: the zero sweep after rst (all words), else one axis's zero or counting sweep at a
    // time; an idle engine starts the next axis (round robin) that has a request (a clear, a pending
    // sweep, a pulse taken now); a clear of the engine's axis restarts it as that axis's zero sweep
    assign      idle = !act && !zact;
    // requests seen by an idle engine (busy = cp | zp then, so a pulse is taken unless zp: zp wins)
    wire [NAXES-1:0] rz = cnt_clear | zp;                       // zero-sweep requests
    wire [NAXES-1:0] rq = rz | cp | sweep;
    // round robin: the first requesting axis after the last one served (ax), so a request waits for
    // at most one sweep of each other axis
    integer pi;
    reg  [AXW:0] pc;
    reg  [AXW-1:0] pick_rr;
    always @(*) begin
        pick_rr = {AXW{1'b0}};
        for (pi = NAXES - 1; pi >= 0; pi = pi - 1) begin
            pc = {1'b0, ax} + 1'b1 + pi[AXW:0];
            if (pc >= NAX) pc = pc - NAX;
            if (rq[pc[AXW-1:0]]) pick_rr = pc[AXW-1:0];
        end
    end
    assign pick = QUEUE ? pick_rr : {AXW{1'b0}};    // (one axis: axis 0)
    assign      start = idle && |rq;
    wire        restart = !zrun && !idle && cnt_clear[ax];     // a clear of the engine's axis
    always @(posedge clk) begin
        if (rst) begin
            act <= 1'b0;
            zact <= 1'b1;
            zall <= 1'b1;
            ax <= {AXW{1'b0}};
            k <= {AW{1'b0}};
            q_ok <= 1'b0;
            hide_st <= 1'b1;
            hide_cnt <= {NAXES{1'b1}};
            cp <= {NAXES{1'b0}};
            zp <= {NAXES{1'b0}};
        end else begin
            q_ok <= act;                // word k's read was issued in this clock (act: not the start clock)
            hide_cnt <= hide_cnt | cnt_clear;
            if (QUEUE) begin
                // requests the engine does not serve now wait; a clear cancels a pending counting sweep;
                // the zero sweep after rst covers every clear
                cp <= (cp | take) & ~cnt_clear & ~served;
                zp <= (zp | (cnt_clear & ~on_ax & {NAXES{!zrun}})) & ~served;
            end
            if (zrun && |cnt_clear) begin
                // a clear during the zero sweep after rst holds it one clock (it stays whole)
            end else if (restart) begin
                act <= 1'b0;
                zact <= 1'b1;
                k <= {AW{1'b0}};
            end else if (start) begin
                ax <= pick;
                k <= {AW{1'b0}};
                act <= !rz[pick];
                zact <= rz[pick];
            end else if (go) begin
                k <= k + {{(AW-1){1'b0}}, 1'b1};
                if (k == k_last) begin
                    act <= 1'b0;
                    zact <= 1'b0;
                    zall <= 1'b0;
                    if (zact) begin
                        // (a clear in this clock took the branches above)
                        if (zall) begin
                            hide_st <= 1'b0;
                            hide_cnt <= {NAXES{1'b0}};
                        end else begin
                            hide_cnt[ax] <= 1'b0;
                        end
                    end
                end
            end
        end
    end
endmodule
`default_nettype wire
