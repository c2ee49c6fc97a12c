// pwm_center: centre-aligned PWM for NCH half-bridges, double-buffered compare,
// dead time (complementary mode) or PWM + enable mode, latched fault, sync.
//
// Counter: up/down 0,1,..,P-1,P,P-1,..,1 (period 2P clocks, P = PWM_HALF_PERIOD,
// 2500 -> 20 kHz at 100 MHz).  Period boundary = counter 0 (start of up-count),
// period centre = counter P.  Ideal high-side command of channel i
//     h_i = (up-count) ? cnt < cmp_i : cnt <= cmp_i
// is high for exactly 2*cmp_i clocks per period (duty cmp_i/P, 0 = off, P = on),
// at the start and at the end of the period, i.e. every period is symmetric
// about its centre and all high sides are off (low sides on) in an off-window
// centred on the centre, where the low-side shunts measure: adc_trig marks it.
//
// Pipeline: stage A = counter/active-compare registers, stage B = the output
// registers (every output below is a flip-flop, nothing combinational after
// it).  Outputs in cycle t+1 show stage-A counter value of cycle t; the model
// (gen/empc/rtlmodel/pwm_center.py) and docs/blocks/pwm_center.md define
// every cycle.
//
// Ports
//   clk, rst           clock, synchronous active-high reset
//   enable             1 = run.  0 -> all outputs off at the next clock edge;
//                      0->1 starts the outputs at the next period boundary.
//   mode               0 = complementary hi/lo with dead time, 1 = PWM + enable
//                      (hi = PWM command, lo = bridge enable); sampled at the
//                      period boundary (the dead-time logic starts from the
//                      present pin state, so a switch cannot overlap hi/lo).
//   dead[DEAD_W-1:0]   dead time in clocks (complementary mode): a switch turns
//                      on only after `dead` clocks with both switches off.
//   cmp_in[NCH*CW-1:0] compare values (channel i in bits i*CW +: CW), 0..P,
//                      values > P act as P (clipped; cmp_clip pulse)
//   cmp_load           write cmp_in into the shadow registers; the shadow is
//                      copied to the active compare at the next period boundary
//   sync_in            rising edge restarts the counter at the boundary (PHASE > 0:
//                      at its phase, see below); synchronous if SYNC_STAGES = 0,
//                      else through sync_2ff
//   fault              synchronous fault (all switches off at the next edge)
//   fault_clear        clears the fault latch if fault is low
//   hi[NCH-1:0]        high-side switch (mode 0) / PWM input (mode 1)
//   lo[NCH-1:0]        low-side switch (mode 0) / bridge enable (mode 1)
//   period_start       1 clock at each period boundary (aligned with hi/lo)
//   adc_trig           1 clock at each period centre (aligned with hi/lo)
//   sync_out           1 clock, SYNC_LEAD clocks before period_start
//   fault_latched      fault latch (1 from the clock after fault until cleared)
//   on                 the outputs are switching (registered with hi/lo: 1 while the
//                      channels run, 0 in every clock in which hi/lo are forced off) -
//                      the real output state for status and for holding the controller
//   mode_eff           output mode currently applied to hi/lo
//   cmp_clip           1 clock after a cmp_load that clipped a value to P
// Parameters
//   NCH                half-bridges (3)
//   PWM_HALF_PERIOD    P, clocks per half period (`EMPC_PWM_HALF_PERIOD`), >= 2
//   CW                 compare/counter width, clog2(P+1)
//   DEAD_W             dead-time width (dead 0..2**DEAD_W-1 clocks)
//   SYNC_STAGES        0 = sync_in synchronous, >= 2 = sync_2ff depth
//   SYNC_LEAD          sync_out lead over period_start, 0..P; a slave fed from
//                      sync_out runs in phase if SYNC_LEAD = 2 + its SYNC_STAGES
//   PHASE              carrier delay in clocks, 0..2P-1 (docs/four_axes.md D4: axis n of
//                      NAXES = 4 gets n * `EMPC_PWM_STAGGER_4).  The counter starts at
//                      reset at position 2P - PHASE of its period (position 0 = boundary,
//                      P = centre), so counter, period_start, adc_trig and sync_out are
//                      those of a PHASE = 0 instance delayed by PHASE clocks, from the first
//                      clock after reset (the periodic waveform: before the first boundary
//                      the end of a period; adc_trig comes before the first period_start
//                      if PHASE > P).  A sync_in rise restarts the counter at the same
//                      position (PHASE clocks before its boundary), so the strobes are again
//                      those of a PHASE = 0 instance restarted by the same rise, delayed by
//                      PHASE; that restart is no boundary: the outputs go off and restart
//                      at the next boundary (as after enable; cmp and mode are taken there).
//                      PHASE = 0: the block as before.
// Latency: cmp_load -> effective at the next period boundary; fault/enable low ->
//   outputs off 1 clock later; sync_in rise -> period_start 2 + SYNC_STAGES later.
// Reset: counter 0 (boundary; PHASE > 0: position 2P - PHASE), shadow/active compare 0,
//   mode 0, outputs off, fault latch clear, not running (needs enable and a boundary to start).
`default_nettype none
`ifndef EMPC_PWM_HALF_PERIOD
`include "empc_formats.vh"
`endif
module pwm_center #(
    parameter integer NCH = 3,
    parameter integer PWM_HALF_PERIOD = `EMPC_PWM_HALF_PERIOD,
    parameter integer CW = $clog2(PWM_HALF_PERIOD + 1),
    parameter integer DEAD_W = 8,
    parameter integer SYNC_STAGES = 0,
    parameter integer SYNC_LEAD = 2,
    parameter integer PHASE = 0
) (
    input  wire              clk,
    input  wire              rst,
    input  wire              enable,
    input  wire              mode,
    input  wire [DEAD_W-1:0] dead,
    input  wire [NCH*CW-1:0] cmp_in,
    input  wire              cmp_load,
    input  wire              sync_in,
    input  wire              fault,
    input  wire              fault_clear,
    output reg  [NCH-1:0]    hi,
    output reg  [NCH-1:0]    lo,
    output reg               period_start,
    output reg               adc_trig,
    output reg               sync_out,
    output reg               fault_latched,
    output reg               on,
    output reg               mode_eff,
    output reg               cmp_clip
);
    localparam [CW-1:0] P = PWM_HALF_PERIOD[CW-1:0];
    localparam [CW-1:0] P_M1 = P - 1'b1;
    localparam [CW-1:0] ONE = {{(CW-1){1'b0}}, 1'b1};
    localparam [CW-1:0] LEAD = SYNC_LEAD[CW-1:0];
    localparam          LEAD_DIR = (SYNC_LEAD == 0) ? 1'b1 : 1'b0;
    localparam          MODE_COMPL = 1'b0;
    // the counter's start (reset, and a sync_in rise when PHASE > 0): period position POS0
    localparam integer  POS0 = (PHASE == 0) ? 0 : 2 * PWM_HALF_PERIOD - PHASE;
    localparam integer  CNT0_I = (POS0 < PWM_HALF_PERIOD) ? POS0 : 2 * PWM_HALF_PERIOD - POS0;
    localparam [CW-1:0] CNT0 = CNT0_I[CW-1:0];
    localparam          DIR0 = (POS0 < PWM_HALF_PERIOD) ? 1'b1 : 1'b0;
    localparam          DIRP0 = (PHASE == 0 || POS0 - 1 < PWM_HALF_PERIOD) ? 1'b1 : 1'b0;  // dir at POS0 - 1
    localparam          SHIFTED = (PHASE != 0) ? 1'b1 : 1'b0;
    generate if (PHASE < 0 || PHASE >= 2 * PWM_HALF_PERIOD) begin : g_bad_phase
        pwm_center_phase_out_of_range u_error ();   // no such module: elaboration stops here
    end endgenerate

    // ---- sync input: optional synchroniser, rising-edge detect ----------------
    wire sync_s;
    generate
        if (SYNC_STAGES > 0) begin : g_sync
            sync_2ff #(.WIDTH(1), .STAGES(SYNC_STAGES)) u_sync (
                .clk(clk), .rst(rst), .d(sync_in), .q(sync_s));
        end else begin : g_nosync
            assign sync_s = sync_in;
        end
    endgenerate
    reg  sync_prev;
    wire sync_rise = sync_s & ~sync_prev;

    // ---- stage A: counter, shadow / active compare, run state -------------------
    reg  [CW-1:0]     cnt;
    reg               dir;          // 1 = up-count (cnt 0..P-1), 0 = down (P..1)
    reg  [NCH*CW-1:0] shadow;
    reg  [NCH*CW-1:0] cmp_act;
    reg               mode_act;
    reg               run;
    wire jump;                                          // PHASE > 0: a sync rise restarts at POS0
    wire bnd_edge;                                      // next cycle is a boundary
    generate if (PHASE > 0) begin : g_phase
        assign jump = sync_rise;
        assign bnd_edge = ~dir & (cnt <= ONE) & ~sync_rise;
    end else begin : g_nophase
        assign jump = 1'b0;
        assign bnd_edge = (~dir & (cnt <= ONE)) | sync_rise;
    end endgenerate
    wire ok = enable & ~fault & ~fault_latched;
    wire alive = run & ok;
    // decodes from the previous clock instead of counter compares: the boundary state
    // (counter 0, up) is exactly the clock after bnd_edge (or rst), the centre (counter P,
    // down) exactly the clock after dir turned 1 -> 0
    reg  at_bnd;
    reg  dir_prev;

    // Values > P are stored unclipped: the counter never leaves [0, P] (up 0..P-1,
    // down P..1), so cnt < c / cnt <= c give the same command for any c >= P as for
    // c = P (always on).  Only the clip flag needs the comparison.
    reg               any_clip;
    integer k;
    always @(*) begin
        any_clip = 1'b0;
        for (k = 0; k < NCH; k = k + 1)
            if (cmp_in[k*CW +: CW] > P) any_clip = 1'b1;
    end

    always @(posedge clk) begin
        if (rst) begin
            sync_prev     <= 1'b0;
            at_bnd        <= ~SHIFTED;
            dir_prev      <= DIRP0;
            cnt           <= CNT0;
            dir           <= DIR0;
            shadow        <= {(NCH*CW){1'b0}};
            cmp_act       <= {(NCH*CW){1'b0}};
            mode_act      <= MODE_COMPL;
            run           <= 1'b0;
            fault_latched <= 1'b0;
            cmp_clip      <= 1'b0;
        end else begin
            sync_prev <= sync_s;
            at_bnd    <= bnd_edge;
            dir_prev  <= jump ? DIRP0 : dir;
            // one adder: +1 up, -1 down (P-1 -> P at the turn round); 0 at the boundary
            if (jump) begin
                cnt <= CNT0;
                dir <= DIR0;
            end else if (bnd_edge) begin
                cnt <= {CW{1'b0}};
                dir <= 1'b1;
            end else begin
                cnt <= cnt + {{(CW-1){~dir}}, 1'b1};
                if (dir && cnt >= P_M1) dir <= 1'b0;
            end
            if (cmp_load) shadow <= cmp_in;
            cmp_clip <= cmp_load & any_clip;
            if (bnd_edge) begin
                cmp_act  <= shadow;
                mode_act <= mode;
                run      <= ok;
            end else begin
                run      <= alive & ~jump;
            end
            fault_latched <= fault | (fault_latched & ~fault_clear);
        end
    end

    // ---- stage B: output registers ------------------------------------------------
    always @(posedge clk) begin
        if (rst) begin
            period_start <= 1'b0;
            adc_trig     <= 1'b0;
            sync_out     <= 1'b0;
            mode_eff     <= MODE_COMPL;
            on           <= 1'b0;
        end else begin
            period_start <= at_bnd;                        // dir & (cnt == 0)
            adc_trig     <= ~dir & dir_prev;                // ~dir & (cnt == P)
            sync_out     <= (dir == LEAD_DIR) & (cnt == LEAD);
            mode_eff     <= mode_act;
            on           <= alive;
        end
    end

    // counter in groups of EG bits (one LUT6 per group compares it with a compare value)
    localparam integer EG = 3;
    localparam integer NG = (CW + EG - 1) / EG;
    /* verilator lint_off UNUSEDSIGNAL */ // top bit: padding only
    wire [EG*NG:0] cnt_x = {{(EG*NG - CW + 1){1'b0}}, cnt};
    /* verilator lint_on UNUSEDSIGNAL */

    genvar i, g;
    generate
        for (i = 0; i < NCH; i = i + 1) begin : g_ch
            wire [CW-1:0] c = cmp_act[i*CW +: CW];
            // ideal high-side command h = dir ? (cnt < c) : (cnt <= c), built from the previous
            // clock's h and one equality (~4 LUTs instead of a magnitude compare): c is constant
            // between boundaries and cnt steps by 1 (0 at a boundary, up 0..P-1, P, down
            // P-1..1), so h changes only where cnt == c.  Up-count: h = (boundary or h_prev) &
            // (cnt != c) (at the boundary h = 0 < c = c != 0); down-count: h = h_prev | (cnt == c)
            // (also at the turn P-1 -> P, where P-1 < c <=> P <= c).
            /* verilator lint_off UNUSEDSIGNAL */ // top bit: padding only
            wire [EG*NG:0] c_x = {{(EG*NG - CW + 1){1'b0}}, c};
            /* verilator lint_on UNUSEDSIGNAL */
            wire [NG-1:0] eqg;                         // per group cnt == c
            for (g = 0; g < NG; g = g + 1) begin : g_eq
                assign eqg[g] = (cnt_x[EG*g +: EG] == c_x[EG*g +: EG]);
            end
            wire [NG:0] eqc = {1'b0, eqg} + {{NG{1'b0}}, 1'b1};   // AND of the groups on a carry chain
            wire eq = eqc[NG];
            reg  h_prev;
            wire h = dir ? (~eq & (h_prev | at_bnd)) : (h_prev | eq);
            reg  [DEAD_W-1:0] q;                       // clocks with hi = lo = 0
            // saturating at 2**DEAD_W-1: the incrementer's carry out is q == Q_MAX
            wire [DEAD_W:0]   q_p1 = {1'b0, q} + {{DEAD_W{1'b0}}, 1'b1};
            wire q_ok = (q >= dead);
            reg  hi_n, lo_n;
            always @(*) begin
                if (~alive) begin
                    hi_n = 1'b0;
                    lo_n = 1'b0;
                end else if (mode_act != MODE_COMPL) begin
                    hi_n = h;                          // PWM command
                    lo_n = 1'b1;                       // bridge enable
                end else begin
                    hi_n = h & (hi[i] | q_ok);
                    lo_n = ~h & (lo[i] | q_ok);
                end
            end
            always @(posedge clk) begin
                if (rst) begin
                    hi[i] <= 1'b0;
                    lo[i] <= 1'b0;
                    h_prev <= 1'b0;
                    q     <= {DEAD_W{1'b0}};
                end else begin
                    hi[i] <= hi_n;
                    lo[i] <= lo_n;
                    h_prev <= h;
                    if (hi_n | lo_n) q <= {DEAD_W{1'b0}};
                    else if (!q_p1[DEAD_W]) q <= q_p1[DEAD_W-1:0];
                end
            end
        end
    endgenerate
endmodule
`default_nettype wire
