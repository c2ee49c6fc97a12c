// axis_status: the status words and event counters of one axis, in one block RAM.
//
// Words (register offsets, empc_regs.vh): the status words SPEED, I_D, I_Q, U_D, U_Q, REF and
// the counters SAT_OPERAND .. CNT_OVERRUN (13 words from SAT_OPERAND on, counter i counts
// event i), PERIODS and SAT_GOV, stored at their offsets in a 64 x 32 block RAM.  This block owns the
// memory, the events of the control period, the zero and counter sweeps' bookkeeping and the
// counter increment; ctrl_seq's engine supplies the clock of the sweeps (their steps are
// microprogram steps: they occupy the engine, which matters for its timing) and the status
// words, which it streams while they pass through its datapath.
//
// Word stream (from ctrl_seq, bit-serial, LSB first): a bit enters the shift register sts with
// st_sh, and st_wr writes sts to word st_addr in one clock (port A).  Port A is shared with
// the CPU read: a write that meets reg_rd waits one clock, so a read never sees a half-written
// word (reads come at most every other clock: emc_bus, one per bus cycle).
// Sweeps: sw_req asks the engine for a sweep (a control period has run, or words are hidden);
// sw_all asks for the zero sweep after rst, which zeroes the status words too.  The engine
// starts it when idle (sw_go), streams its words one by one (33 clocks each: bits 0..31 with
// st_sh, st_wr after them) and marks its end with sw_end; ctl_go (the start of a control
// period) abandons a sweep in progress and makes the next one due.  In a sweep this block
// supplies the bits itself: counter + event (port B reads bit st_bit of word st_addr one
// clock ahead, a 1-bit carry adds the event held for that counter), saturating at 2^32-1
// (the write is dropped; PERIODS wraps), or 0 in a zero sweep (after rst or cnt_clear, until
// a zero sweep has run to its end: the hidden words read 0 from the command on).
// Events (held from the update to the end of the next sweep, so SAT_* and CNT_OVERRUN count
// the control periods in which the event happened): core_flags at core_done (SAT_OPERAND ..
// SAT_SIGNAL), front_sat (SAT_FRONT), overrun (CNT_OVERRUN), period (PERIODS), gov (SAT_GOV: the
// reference governor shaped the reference).
//
// Ports: reg_rd / reg_addr -> rdata, valid the clock after reg_rd, 0 unless a word of this
// block is read (ORed into the axis read data).  Latency: a word written by st_wr reads from
// the next clock on (two clocks if st_wr met a read).  No parameters (the offsets come from
// empc_regs.vh; elaboration stops if the counters are not contiguous below 64).
// Reset: events 0, no sweep pending, all words hidden until the zero sweep (requested at
// once) has ended; the memory itself is not reset.
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
    input  wire [10:0] core_flags,      // mpc_core flags (FLAG_BITS): SAT_OPERAND ..
    input  wire        front_sat,       // pulse: a front-end block saturated (SAT_FRONT)
    input  wire        overrun,         // pulse: a period missed its boundary (CNT_OVERRUN)
    input  wire        period,          // pulse: a control period ran with the law active (PERIODS)
    input  wire        gov,             // pulse: the reference governor clamped or held (SAT_GOV)
    // word stream from ctrl_seq
    input  wire        st_sh,
    input  wire        st_d,
    input  wire        st_wr,
    input  wire [5:0]  st_addr,
    input  wire [4:0]  st_bit,          // bit of word st_addr that st_sh takes next clock
    // sweep handshake with ctrl_seq
    output wire        sw_req,
    output wire        sw_all,
    input  wire        sw_go,
    input  wire        sw_end,
    input  wire        ctl_go
);
    localparam integer A_CNT0 = `EMPC_A_SAT_OPERAND;    // counter of event i: A_CNT0 + i
    localparam integer NEV = 13;                        // events with a counter from A_CNT0 on
    localparam integer A_CNT_LAST = A_CNT0 + NEV - 1;

    generate if (`EMPC_A_CNT_OVERRUN != A_CNT_LAST || `EMPC_A_SAT_FRONT != A_CNT_LAST - 1 || A_CNT_LAST > 63 ||
                 `EMPC_A_PERIODS > 63 || `EMPC_A_SAT_GOV > 63 || `EMPC_A_I_D > 63 || `EMPC_A_REF > 63 ||
                 `EMPC_A_SPEED > 63)
    begin : g_bad_map
        axis_status_unsupported_register_map u_error ();   // no such module: elaboration stops here
    end endgenerate

    // ---------------- events of the control period ----------------
    reg  [10:0] ev_core;
    reg         ev_front, ev_ovr, ev_per, ev_gov;
    always @(posedge clk) begin
        if (rst || sw_end) begin
            ev_core <= 11'd0;
            ev_front <= 1'b0;
            ev_ovr <= 1'b0;
            ev_per <= 1'b0;
            ev_gov <= 1'b0;
        end else begin
            if (core_done) ev_core <= core_flags;
            if (front_sat) ev_front <= 1'b1;
            if (overrun) ev_ovr <= 1'b1;
            if (period) ev_per <= 1'b1;
            if (gov) ev_gov <= 1'b1;
        end
    end
    // event bit of each word (0 for the status words)
    wire [63:0] ev_at = ({{(64 - NEV){1'b0}}, ev_ovr, ev_front, ev_core} << A_CNT0) |
                        ({63'd0, ev_per} << `EMPC_A_PERIODS) | ({63'd0, ev_gov} << `EMPC_A_SAT_GOV);

    // ---------------- sweeps ----------------
    reg         hide_st, hide_cnt;  // status words / counters hidden until a zero sweep ends
    reg         pend;               // a control period has run: its counter sweep is due
    reg         swp, cz;            // a sweep is running; it is a zero sweep
    assign sw_req = hide_st || hide_cnt || pend;
    assign sw_all = hide_st;
    always @(posedge clk) begin
        if (rst) begin
            hide_st <= 1'b1;
            hide_cnt <= 1'b1;
            pend <= 1'b0;
            swp <= 1'b0;
            cz <= 1'b0;
        end else begin
            if (sw_go) begin
                swp <= 1'b1;
                cz <= hide_cnt;
                pend <= 1'b0;
            end
            if (ctl_go) begin
                swp <= 1'b0;
                cz <= 1'b0;
                pend <= 1'b1;
            end
            if (sw_end) begin
                swp <= 1'b0;
                if (cz) begin
                    hide_cnt <= 1'b0;
                    hide_st <= 1'b0;
                end
            end
            if (cnt_clear) hide_cnt <= 1'b1;
        end
    end

    // ---------------- memory ----------------
    reg         smem [0:2047];      // 64 words x 32 bit, bit {word, bit}
    integer si;
    initial begin
        for (si = 0; si < 2048; si = si + 1) smem[si] = 1'b0;
    end
    // counter + event: port B reads bit st_bit of word st_addr one clock before it is added; the
    // carry is preset with the word's event in every clock without a bit (the engine's E_OP clock
    // before the word), so after bit 31 it is the carry out: the counter was 2^32-1
    reg         cnt_q, c;
    always @(posedge clk) begin
        cnt_q <= smem[{st_addr, st_bit}];
        c <= st_sh ? (cnt_q & c) : (ev_at[st_addr] && !cz);
    end
    wire        saturated = swp && c && !cz && (st_addr != `EMPC_A_PERIODS);
    reg  [31:0] sts;
    always @(posedge clk) begin
        if (st_sh) sts <= {swp ? ((cnt_q ^ c) && !cz) : st_d, sts[31:1]};
    end
    // port A: CPU read, or the write of sts (moved by one clock when it meets a CPU read)
    wire        wr = st_wr && !saturated;
    reg         w_def;
    reg  [5:0]  w_def_a;
    wire        w_go = (wr && !reg_rd) || w_def;
    wire [5:0]  w_a  = w_def ? w_def_a : st_addr;
    always @(posedge clk) begin
        w_def <= wr && reg_rd && !rst;
        w_def_a <= st_addr;
    end
    wire        s_rd = (cnt_re && !hide_cnt) || (stat_re && !hide_st);
    wire [5:0]  pa = w_go ? w_a : reg_addr[5:0];   // (a write never meets a read)
    wire        unused_addr = &{1'b0, reg_addr[7:6]};   // cnt_re / stat_re already decode the page
    always @(posedge clk) begin
        if (w_go)
            for (si = 0; si < 32; si = si + 1) smem[{pa, si[4:0]}] <= sts[si];
        if (!s_rd)
            rdata <= 32'd0;
        else
            for (si = 0; si < 32; si = si + 1) rdata[si] <= smem[{pa, si[4:0]}];
    end
endmodule
`default_nettype wire
