// out_kill: clock-independent kill path between the bridge-command registers and the pins.
//
//   q = d & kill_n,
//   kill_n = pwr_fault_n & locked & rst_n_in & ~clk_dead & ~cap_ps & ~cap_ck & ~ps_s & ~ck_s
//
// A combinational gate (one LUT per output plus two shared LUTs for kill_n): when the power
// stage reports a fault (pwr_fault_n low), the PLL is not locked, the board reset is held,
// the fabric clock is declared dead, or a kill event has been captured and not yet taken over by the synchronous fault latch,
// every output is 0 without any clock edge.  Deliberately asynchronous: the clock may be
// what failed.
//
// Capture (so that any kill event, however short, is latched and the outputs cannot come
// back before the synchronous path holds them off):
//   cap_ps  asynchronously SET by pwr_fault_n low;
//   cap_ck  asynchronously SET by a PLL lock loss or by clk_dead (clk_mon: the fabric
//           clock stopped, seen from the configuration oscillator);
//   both only once `armed` (sticky, set by the first clock with rst low after
//   configuration): the start-up (PLL not yet locked, power stage still powering up) turns
//   the outputs off through the gate and the reset but latches no fault; from then on every
//   event is captured, also during a later reset (it is reported when the reset ends);
//   each goes through a sync_2ff (the named crossing) to ps_s / ck_s = the fault causes
//   `pstage` / `clock` for fault_ctrl, and is cleared synchronously once its synchronised
//   copy is 1 and rst is low (the fault latch, out of reset, has seen the cause), unless
//   its set input is still active.  A cause is therefore high for >= 3 clocks after rst is
//   low; the outputs stay gated until ps_s / ck_s fall, 2 clocks after the capture is
//   cleared, by which time the fault latch (not maskable for these causes, mpc_axis) has
//   held the registered outputs d at 0 for >= 2 clocks.
// Asynchronous set flip-flops are the one deliberate exception to the synchronous-reset
// rule: a clocked capture could miss a pulse shorter than a clock or a pulse while the
// clock is stopped.
//
// Glitches: kill_n is an AND (monotone): a transient on any kill input can only turn the
// outputs off.  Every release (pwr_fault_n, locked or rst_n_in rising; a capture or a
// synchronised cause falling) happens while d is already 0 (fault latched, or reset), so a
// LUT transient during a release cannot produce an output pulse; a single-input change of
// a LUT whose output does not change is glitch-free.  A kill while d = 1 is a single
// transition towards 0 (several kill inputs changing together pass only through off
// states).  d changing while kill_n = 1 is one clean transition, as without the gate.
//
// Ports:
//   clk, rst        fabric clock, synchronous reset (clk_gen)
//   d[W]            registered bridge commands (pwm_center hi / lo of every axis)
//   pwr_fault_n     power-stage fault pin, active low, asynchronous (LX_PWR)
//   rst_n_in        board reset pin, active low, asynchronous
//   locked          PLL lock, asynchronous to clk
//   clk_dead        clk_mon output (oscillator domain), asynchronous to clk
//   q[W]            to the output pads
//   pstage, clock   synchronised fault causes (levels, clk domain)
// Parameters: W (outputs).
// Latency: pin / lock / clk_dead -> q = 0: combinational (0 clock edges; pad-to-pad delay,
//   see docs/safety.md); -> pstage / clock: 2-3 clocks after rst is low (sync_2ff).
// Reset: rst does not clear the captures or `armed` (a kill event during a reset is reported
//   after it); initial values 0 (FPGA INIT).
// Resources: 7 flip-flops (2 with asynchronous preset), W + 3 LUTs.
`default_nettype none
module out_kill #(
    parameter integer W = 6
) (
    input  wire         clk,
    input  wire         rst,
    input  wire [W-1:0] d,
    input  wire         pwr_fault_n,
    input  wire         rst_n_in,
    input  wire         locked,
    input  wire         clk_dead,
    output wire [W-1:0] q,
    output wire         pstage,
    output wire         clock
);
    reg armed;                                  // rst was released once since configuration (sticky)
    initial armed = 1'b0;
    always @(posedge clk) if (!rst) armed <= 1'b1;

    wire set_ps = armed && !pwr_fault_n;
    wire set_ck = armed && (!locked || clk_dead);
    reg  cap_ps, cap_ck;
    initial begin
        cap_ps = 1'b0;
        cap_ck = 1'b0;
    end
    wire ps_s, ck_s;
    sync_2ff #(.WIDTH(2)) u_sync (.clk(clk), .rst(1'b0), .d({cap_ck, cap_ps}), .q({ck_s, ps_s}));
    always @(posedge clk or posedge set_ps) begin
        if (set_ps)             cap_ps <= 1'b1;
        else if (ps_s && !rst)  cap_ps <= 1'b0;
    end
    always @(posedge clk or posedge set_ck) begin
        if (set_ck)             cap_ck <= 1'b1;
        else if (ck_s && !rst)  cap_ck <= 1'b0;
    end

    wire kill_n = pwr_fault_n & locked & rst_n_in & ~clk_dead & ~cap_ps & ~cap_ck & ~ps_s & ~ck_s;
    assign q = d & {W{kill_n}};
    assign pstage = ps_s;
    assign clock = ck_s;
`ifdef FORMAL
    // ---------------- properties (formal/out_kill.sby, SymbiYosys with `multiclock on`) ----------------
    // Every input, the clock included, is free at every solver step: a step may hold no clock
    // edge, a pulse may be shorter than a clock period, the clock may stop for any time; the
    // asynchronous presets act within their step.  f_* is the properties' own reference state.
    // Contract of the downstream logic (proved there, assumed here): d are registers (change
    // only at a rising clk edge) and are 0 after every edge at which the fault trip was high
    // (fault_ctrl: trip = latched | cause for these non-maskable causes; pwm_center P3: all
    // outputs 0 the clock after `fault`) or rst was high (pwm_center reset).
    //  K1  no clock needed: while pwr_fault_n, locked or rst_n_in is low or clk_dead is high,
    //      q = 0 (in the same step)
    //  K2  after a power-stage event (pwr_fault_n low, armed), q = 0 until `pstage` has been
    //      taken at a rising edge with rst low (the fault latch holds it from there) and one
    //      more rising edge has passed; the same for a clock event and `clock`
    //  K3  the cause is raised: at most 2 rising edges with rst low pass after an event before
    //      the cause is taken (bounded model check, task bmc)
    reg         f_init = 1'b1, f_pclk = 1'b1, f_prst = 1'b1, f_pps = 1'b0, f_pck = 1'b0, f_armed = 1'b0;
    reg         f_lat_ps = 1'b0, f_lat_ck = 1'b0;
    reg [W-1:0] f_pd = {W{1'b0}};
    (* anyseq *) reg f_clr;                     // CPU fault clear at an edge (any time)
    wire        f_rise = clk && !f_pclk;
    wire        f_take = f_rise && !f_prst;     // an edge at which the fault latch samples
    wire        f_armed_now = f_armed || f_take;
    wire        f_ev_ps = f_armed_now && !pwr_fault_n;
    wire        f_ev_ck = f_armed_now && (!locked || clk_dead);
    // reference event state, *_n = the value in this step (the flip-flops of the DUT change in
    // the step of the edge, so the reference is evaluated with the same timing)
    reg         f_pend_ps = 1'b0, f_pend_ck = 1'b0, f_seen_ps = 1'b0, f_seen_ck = 1'b0;
    reg  [1:0]  f_wait_ps = 2'd0, f_wait_ck = 2'd0;
    wire        f_pend_ps_n = f_ev_ps || (f_pend_ps && !(f_rise && f_seen_ps));
    wire        f_seen_ps_n = !f_ev_ps && (f_seen_ps || (f_pend_ps && f_take && f_pps));
    wire [1:0]  f_wait_ps_n = f_ev_ps ? 2'd0 : (f_pend_ps && f_take && !f_seen_ps && !f_pps && f_wait_ps != 2'd3)
                              ? f_wait_ps + 2'd1 : f_wait_ps;
    wire        f_pend_ck_n = f_ev_ck || (f_pend_ck && !(f_rise && f_seen_ck));
    wire        f_seen_ck_n = !f_ev_ck && (f_seen_ck || (f_pend_ck && f_take && f_pck));
    wire [1:0]  f_wait_ck_n = f_ev_ck ? 2'd0 : (f_pend_ck && f_take && !f_seen_ck && !f_pck && f_wait_ck != 2'd3)
                              ? f_wait_ck + 2'd1 : f_wait_ck;
    always @($global_clock) begin
        f_init <= 1'b0;
        f_pclk <= clk;
        f_prst <= rst;
        f_pps <= ps_s;
        f_pck <= ck_s;
        f_pd <= d;
        f_armed <= f_armed_now;
        if (f_rise) begin
            f_lat_ps <= f_prst ? 1'b0 : f_clr ? f_pps : (f_lat_ps | f_pps);
            f_lat_ck <= f_prst ? 1'b0 : f_clr ? f_pck : (f_lat_ck | f_pck);
        end
        f_pend_ps <= f_pend_ps_n;
        f_seen_ps <= f_seen_ps_n;
        f_wait_ps <= f_wait_ps_n;
        f_pend_ck <= f_pend_ck_n;
        f_seen_ck <= f_seen_ck_n;
        f_wait_ck <= f_wait_ck_n;
    end
    always @(*) begin
        if (f_init) assume(rst && !armed && !cap_ps && !cap_ck && !ps_s && !ck_s);   // configuration
        // the downstream contract
        if (!f_init && !f_rise) assume(d == f_pd);
        if (!f_init && f_rise && (f_prst || f_lat_ps || f_lat_ck || f_pps || f_pck)) assume(d == {W{1'b0}});
        if (!f_init) begin
            // K1
            if (!pwr_fault_n || !locked || !rst_n_in || clk_dead) assert(q == {W{1'b0}});
            // K2
            if (f_pend_ps_n || f_pend_ck_n) assert(q == {W{1'b0}});
`ifdef KILL_K3
            // K3 (bounded task: its inductive invariant would need the synchroniser's first stage)
            assert(f_wait_ps_n <= 2'd2 && f_wait_ck_n <= 2'd2);
`endif
            // invariants (make K2 / K3 inductive): the mirror of armed; a pending event that
            // has not been taken is still captured; once taken, the registers are 0
            assert(armed == f_armed_now);
            if (f_pend_ps_n && !f_seen_ps_n) assert(cap_ps);
            if (f_pend_ck_n && !f_seen_ck_n) assert(cap_ck);
            if ((f_pend_ps_n && f_seen_ps_n) || (f_pend_ck_n && f_seen_ck_n)) assert(d == {W{1'b0}});
        end
    end
`ifdef KILL_COVER
    reg f_back = 1'b0;
    always @($global_clock) if (f_pend_ps && f_rise && f_seen_ps) f_back <= 1'b1;
    always @(*) if (!f_init) begin
        cover(f_back && q != {W{1'b0}} && !f_pend_ps_n && !f_pend_ck_n);    // back on after a pstage event
        cover(!pwr_fault_n && !f_rise && f_pclk && d != {W{1'b0}} && armed);  // kill between two edges
        cover(f_pend_ck && f_rise && f_seen_ck && !rst);                    // a clock event taken over
    end
`endif
`endif
endmodule
`default_nettype wire
