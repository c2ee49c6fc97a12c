// pwm_center_props: formal property wrapper for rtl/pwm_center.v (SymbiYosys,
// formal/pwm_center.sby, run by flow/formal.py).  Every DUT input is a free
// input of this wrapper (any value on any clock, including rst, sync_in, mode,
// dead, cmp_in/cmp_load, fault, fault_clear); only the first clock is a reset.
// The properties look at the DUT ports only and keep their own reference
// state (fault latch, off-counters); they are proved by k-induction.
//
//  P1  complementary mode (mode_eff = 0): hi[i] & lo[i] is never 1
//  P2  complementary mode: every off->on transition of hi[i] or lo[i] follows
//      at least `dead` clocks (value of dead at that clock edge) in which both
//      hi[i] and lo[i] were 0
//  P3  the clock after `fault` is 1 every hi/lo output is 0 and fault_latched
//      is 1; all outputs stay 0 and fault_latched stays 1 until fault_clear is
//      seen with fault low (reference latch f_flt == fault_latched)
//  P4  PWM+enable mode (mode_eff = 1): pwm (hi) and en (lo) are 0 while the
//      fault is latched
//  P5  the clock after enable = 0 every output is 0
//  P6  `on` tells the output state: on = 0 -> every hi/lo output is 0; PWM+enable mode:
//      the enables (lo) equal on (STATUS.bridges_on reads the pins)
//  C*  cover: the properties are not vacuous (turn-on after the longest dead
//      time, restart after a fault clear, both modes driving)
`default_nettype none
module pwm_center_props #(
    parameter integer NCH = 3,
    parameter integer P = 12,
    parameter integer DEAD_W = 4,
    parameter integer SYNC_STAGES = 0,
    parameter integer SYNC_LEAD = 2,
    parameter integer PHASE = 0,
    parameter integer CW = $clog2(P + 1)
) (
    input wire              clk,
    input wire              rst,
    input wire              enable,
    input wire              mode,
    input wire [DEAD_W-1:0] dead,
    input wire [NCH*CW-1:0] cmp_in,
    input wire              cmp_load,
    input wire              sync_in,
    input wire              fault,
    input wire              fault_clear
);
    wire [NCH-1:0] hi, lo;
    wire period_start, adc_trig, sync_out, fault_latched, mode_eff, cmp_clip, on;

    pwm_center #(
        .NCH(NCH), .PWM_HALF_PERIOD(P), .CW(CW), .DEAD_W(DEAD_W),
        .SYNC_STAGES(SYNC_STAGES), .SYNC_LEAD(SYNC_LEAD), .PHASE(PHASE)
    ) dut (
        .clk(clk), .rst(rst), .enable(enable), .mode(mode), .dead(dead),
        .cmp_in(cmp_in), .cmp_load(cmp_load), .sync_in(sync_in),
        .fault(fault), .fault_clear(fault_clear),
        .hi(hi), .lo(lo), .period_start(period_start), .adc_trig(adc_trig),
        .sync_out(sync_out), .fault_latched(fault_latched), .mode_eff(mode_eff),
        .cmp_clip(cmp_clip), .on(on)
    );

    localparam [DEAD_W-1:0] DMAX = {DEAD_W{1'b1}};

    // ---- reference state -------------------------------------------------------
    reg              f_valid = 1'b0;     // a previous clock exists
    reg              p_rst, p_fault, p_enable;
    reg [DEAD_W-1:0] p_dead;
    reg [NCH-1:0]    p_hi, p_lo;
    reg              f_flt;              // reference fault latch
    reg              f_restart;          // cover helper: outputs on after a clear

    always @(posedge clk) begin
        f_valid  <= 1'b1;
        p_rst    <= rst;
        p_fault  <= fault;
        p_enable <= enable;
        p_dead   <= dead;
        p_hi     <= hi;
        p_lo     <= lo;
        if (rst) f_flt <= 1'b0;
        else     f_flt <= fault | (f_flt & ~fault_clear);
    end

    always @(*) if (!f_valid) assume(rst);

    // P3 / P4 / P5 and the latch itself
    always @(*) begin
        if (f_valid && !p_rst) begin
            assert(fault_latched == f_flt);
            if (p_fault)   assert(hi == {NCH{1'b0}} && lo == {NCH{1'b0}} && fault_latched);
            if (f_flt)     assert(hi == {NCH{1'b0}} && lo == {NCH{1'b0}});
            if (f_flt && mode_eff) assert(hi == {NCH{1'b0}} && lo == {NCH{1'b0}});   // P4 (pwm, en)
            if (!p_enable) assert(hi == {NCH{1'b0}} && lo == {NCH{1'b0}});
        end
        if (f_valid && p_rst) assert(hi == {NCH{1'b0}} && lo == {NCH{1'b0}} && !fault_latched);
        if (f_valid && !on) assert(hi == {NCH{1'b0}} && lo == {NCH{1'b0}});        // P6
        if (f_valid && mode_eff) assert(lo == {NCH{on}});                          // P6
    end

    genvar i;
    generate
        for (i = 0; i < NCH; i = i + 1) begin : g_ch
            // f_off: clocks with hi = lo = 0, consecutive, ending at the previous clock
            reg [DEAD_W-1:0] f_off = {DEAD_W{1'b0}};
            always @(posedge clk) begin
                if (hi[i] | lo[i])   f_off <= {DEAD_W{1'b0}};
                else if (f_off != DMAX) f_off <= f_off + 1'b1;
            end
            wire turn_on = (hi[i] & ~p_hi[i]) | (lo[i] & ~p_lo[i]);
            always @(*) begin
                if (f_valid && !mode_eff) begin
                    assert(!(hi[i] && lo[i]));                         // P1
                    if (turn_on) assert(f_off >= p_dead);               // P2
                end
            end
`ifdef PWM_COVER
            always @(*) if (f_valid) begin
                cover(!mode_eff && hi[i] && !p_hi[i] && p_dead == DMAX);   // hi after the longest dead time
                cover(!mode_eff && lo[i] && !p_lo[i] && p_dead == DMAX);   // lo after the longest dead time
                cover(mode_eff && hi[i] && lo[i]);                         // PWM+enable driving
            end
`endif
        end
    endgenerate

`ifdef PWM_COVER
    always @(posedge clk) begin
        if (rst || fault) f_restart <= 1'b0;
        else if (f_flt && fault_clear) f_restart <= 1'b1;
    end
    always @(*) if (f_valid) cover(f_restart && (hi != 0 || lo != 0));   // back on after fault + clear
`endif
endmodule
`default_nettype wire
