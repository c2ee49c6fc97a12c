// axis_status: the status words and event counters of one axis, in one block RAM (64 x 32).
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
// Events (held from their pulse to the next counting sweep, so SAT_* and CNT_OVERRUN count the
// control periods in which the event happened): core_flags at core_done (SAT_OPERAND .. SAT_SIGNAL),
// front_sat (SAT_FRONT), overrun (CNT_OVERRUN), period (PERIODS), gov (SAT_GOV).
// Counting sweep (sweep pulse: a control period's job ended): the events, including this clock's,
// are taken and cleared; then counter k = 0..14 is read on port B, +1 if its event, and written
// back on port A when port A is free (saturating at 2^32 - 1: the write is dropped; PERIODS wraps):
// one counter a clock, 16 clocks without CPU traffic.  A sweep pulse while a sweep runs is not
// taken (its events stay held for the next one).
// Zero sweep: after rst all 64 words, after cnt_clear the 15 counters are written 0 (one a clock
// when port A is free); the words stay hidden (read 0) from the rst / command until it ends.  A zero
// sweep abandons a counting sweep; a sweep pulse during a zero sweep is not taken.
//
// Ports: reg_rd / reg_addr -> rdata, valid the clock after reg_rd, 0 unless a word of this block is
// read (ORed into the axis read data).  busy: a sweep runs.  No parameters (offsets from
// empc_regs.vh; elaboration stops if the counters are not contiguous below 64).
// Latency: a word written by st_we reads from the next clock on (two clocks if it met a read); a
// counting sweep ends at most 16 + (clocks port A is taken) clocks after its pulse.
// Reset: events 0, every word hidden until the zero sweep after rst (64 clocks) has ended.
// Bit-exact, clock by clock, to gen/empc/rtlmodel/axis_status.py.
`default_nettype none
`include "empc_regs.vh"
module axis_status (
    input  wire        clk,
    input  wire        rst,
    // CPU read port
    input  wire        reg_rd,          // any CPU read of the axis (port A arbitration)
    input  wire [7:0]  reg_addr,
    input  wire        cnt_re,          // read of a counter word (axis_regs' address table)
    input  wire        stat_re,         // read of a status word (axis_regs' address table)
    output reg  [31:0] rdata,
    input  wire        cnt_clear,       // pulse: zero the counters (CMD.clear_counters)
    // events of the control period
    input  wire        core_done,
    input  wire [10:0] core_flags,
    input  wire        front_sat,
    input  wire        overrun,
    input  wire        period,
    input  wire        gov,
    // status words from the sequencer
    input  wire        st_we,
    input  wire [5:0]  st_addr,         // held (with st_wdata) in the clock after st_we
    input  wire [31:0] st_wdata,
    // counting sweep
    input  wire        sweep,
    output wire        busy
);
    localparam integer A_CNT0 = `EMPC_A_SAT_OPERAND;    // counter of event i: A_CNT0 + i (i < 13)
    localparam integer NEV = 13;
    localparam integer A_CNT_LAST = A_CNT0 + NEV - 1;
    localparam integer NCNT = NEV + 2;                  // + PERIODS, SAT_GOV
    localparam [5:0]   K_NEV = NEV[5:0];

    generate if (`EMPC_A_CNT_OVERRUN != A_CNT_LAST || `EMPC_A_SAT_FRONT != A_CNT_LAST - 1 || A_CNT_LAST > 63 ||
                 `EMPC_A_PERIODS > 63 || `EMPC_A_SAT_GOV > 63 || `EMPC_A_I_D > 63 || `EMPC_A_REF > 63 ||
                 `EMPC_A_SPEED > 63)
    begin : g_bad_map
        axis_status_unsupported_register_map u_error ();   // no such module: elaboration stops here
    end endgenerate

    // ---------------- events ----------------
    reg  [10:0] ev_core;
    reg         ev_front, ev_ovr, ev_per, ev_gov;
    // this clock's events on top of the held ones (what a sweep pulse takes)
    wire [NCNT-1:0] ev_now = {gov | ev_gov, period | ev_per, overrun | ev_ovr, front_sat | ev_front,
                              core_done ? core_flags : ev_core};
    reg         act, zact, zall;    // counting sweep / zero sweep running; the zero sweep is of all words
    reg  [5:0]  k;                  // word of the sweep
    reg  [NCNT-1:0] sev;            // the events the counting sweep adds
    reg         hide_st, hide_cnt;
    wire        take = sweep && !act && !zact;
    always @(posedge clk) begin
        if (rst || take) begin
            ev_core <= 11'd0;
            ev_front <= 1'b0;
            ev_ovr <= 1'b0;
            ev_per <= 1'b0;
            ev_gov <= 1'b0;
        end else begin
            ev_core <= ev_now[10:0];
            ev_front <= ev_now[11];
            ev_ovr <= ev_now[12];
            ev_per <= ev_now[13];
            ev_gov <= ev_now[14];
        end
    end
    // address of sweep word k: the counters in event order, or (zero sweep after rst) word k
    wire [5:0]  cnt_a = (k < K_NEV) ? (A_CNT0[5:0] + k) : (k == K_NEV) ? `EMPC_A_PERIODS : `EMPC_A_SAT_GOV;
    wire [5:0]  sw_a  = zall ? k : cnt_a;
    wire [5:0]  k_last = zall ? 6'd63 : NCNT[5:0] - 6'd1;

    // ---------------- memory ----------------
    (* ram_style = "block" *) reg [31:0] smem [0:63];
    integer si;
    initial begin
        for (si = 0; si < 64; si = si + 1) smem[si] = 32'd0;
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
    wire        cnt_ev = sev[k[3:0]];
    wire        c_full = &q;
    wire        go_c = act && q_ok && a_free;
    wire        go_z = zact && a_free;
    wire        go   = go_c || go_z;
    wire        sw_wr = go_z || (go_c && !(cnt_ev && c_full && cnt_a != `EMPC_A_PERIODS));
    wire [31:0] sw_d  = go_z ? 32'd0 : q + {31'd0, cnt_ev};
    // port B reads word k + 1 when the sweep steps now, else word k: both addresses from registers,
    // `go` (behind the CPU read decode, reg_rd) picks one in the last gate
    wire [5:0]  k1    = k + 6'd1;
    wire [5:0]  cnt_a1 = (k1 < K_NEV) ? (A_CNT0[5:0] + k1) : (k1 == K_NEV) ? `EMPC_A_PERIODS : `EMPC_A_SAT_GOV;
    wire [5:0]  b_addr = go ? cnt_a1 : cnt_a;
    always @(posedge clk) q <= smem[b_addr];
    wire        s_rd = (cnt_re && !hide_cnt) || (stat_re && !hide_st);
    wire [5:0]  pa = reg_rd ? reg_addr[5:0] : w_st ? st_addr : sw_a;
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
    assign busy = act || zact;
    always @(posedge clk) begin
        if (rst) begin
            act <= 1'b0;
            zact <= 1'b1;
            zall <= 1'b1;
            k <= 6'd0;
            q_ok <= 1'b0;
            sev <= {NCNT{1'b0}};
            hide_st <= 1'b1;
            hide_cnt <= 1'b1;
        end else if (cnt_clear) begin
            act <= 1'b0;
            zact <= 1'b1;
            zall <= zall && zact;       // a clear during the zero sweep after rst keeps it whole
            if (!(zall && zact)) k <= 6'd0;
            hide_cnt <= 1'b1;
        end else begin
            if (take) begin
                act <= 1'b1;
                k <= 6'd0;
                sev <= ev_now;
            end else if (go) begin
                k <= k + 6'd1;
                if (k == k_last) begin
                    act <= 1'b0;
                    zact <= 1'b0;
                    zall <= 1'b0;
                    if (zact) begin
                        hide_cnt <= 1'b0;
                        if (zall) hide_st <= 1'b0;
                    end
                end
            end
            q_ok <= act && !take;       // word k's read was issued in this clock
        end
    end
endmodule
`default_nettype wire
