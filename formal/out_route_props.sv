// out_route_props: properties of rtl/out_route.v (issue 16 item 4, docs/four_axes.md 5.3; SymbiYosys,
// formal/out_route.sby, run by flow/formal.py).  Every input is free: the selects (any code, also
// those the register block refuses), the write pulse, the pwm_center pairs, the trips; only the
// first clock is a reset.  The references are built from the previous clock's inputs (p_*).
// For every output k, with c = the code output k selected in the previous clock:
//  R0  a reset clock leaves every pin off
//  R1  c = 0 (or a code beyond the build's pairs) leaves the pin off
//  R2  otherwise the pin pair equals the source pair (c - 1) of the previous clock, unless its axis tripped
//  R3  trip[a] in the previous clock: every output whose code names axis a is off
//  R5  hi and lo of an output are both on only if the source pair was both on
// (R4, the selects change only while every axis is off, is a property of the register block that
// stores them: formal/global_regs_props.sv G4.)
//  R6  mapped[j] (phase j drives an output) only while some output selects j (outside the clock of
//      the write pulse, in which mapped still shows the previous table's scan).  Assumed, as global_regs guarantees (G4):
//      the selects change only at a reset or with the osel_wr pulse in the clock they change.
//  R7  a mapped bit falls only in the clock after a reset or an osel_wr pulse (a scan pass never drops
//      a phase of an unchanged table).  With G4 (osel_wr only while no axis is live) and CTRL.enable 0
//      from reset: mapped[a] cannot fall while an axis is live, so route_ok of an axis that is on stays 1
//      (it can rise while live: an enable within NOUT + 1 clocks of an OUT_SEL write waits for the scan).
`default_nettype none
`include "empc_regs.vh"
module out_route_props #(
    parameter integer NAXES = 4
) (
    input wire                          clk,
    input wire                          rst,
    input wire [`EMPC_ROUTE_OUT_W*`EMPC_ROUTE_OUTPUTS-1:0] osel,
    input wire                          osel_wr,
    input wire [3*NAXES-1:0]            hi,
    input wire [3*NAXES-1:0]            lo,
    input wire [NAXES-1:0]              trip
);
    localparam integer SW = `EMPC_ROUTE_OUT_W, NOUT = `EMPC_ROUTE_OUTPUTS, NP = 3 * NAXES;
    wire [NOUT-1:0] pin_hi, pin_lo;
    wire [NP-1:0] mapped;
    wire bad_sel;
    wire [NP-1:0] ax_miso, ax_hall;
    wire [NAXES-1:0] ax_a, ax_b, ax_i, ax_m;
    // the input multiplexers are combinational (tested in tb/test_out_route.py): constant lines here
    out_route #(.NAXES(NAXES)) dut (
        .clk(clk), .rst(rst), .osel(osel), .osel_wr(osel_wr), .asel({(`EMPC_ROUTE_ADC_W*NP){1'b0}}),
        .esel({(`EMPC_ROUTE_ENC_W*NAXES){1'b0}}), .hsel({(`EMPC_ROUTE_HALL_W*NAXES){1'b0}}), .hi(hi), .lo(lo),
        .trip(trip), .pin_hi(pin_hi), .pin_lo(pin_lo), .miso({`EMPC_ROUTE_ADC{1'b0}}), .ax_miso(ax_miso),
        .irc_a({`EMPC_ROUTE_ENC{1'b0}}), .irc_b({`EMPC_ROUTE_ENC{1'b0}}), .irc_idx({`EMPC_ROUTE_ENC{1'b0}}),
        .irc_mark({`EMPC_ROUTE_ENC{1'b0}}), .ax_irc_a(ax_a), .ax_irc_b(ax_b), .ax_irc_idx(ax_i),
        .ax_irc_mark(ax_m), .hall({(3*`EMPC_ROUTE_HALL){1'b0}}), .ax_hall(ax_hall), .mapped(mapped),
        .bad_sel(bad_sel));

    reg f_pv = 1'b0;
    always @(posedge clk) f_pv <= 1'b1;
    always @(*) if (!f_pv) assume(rst);

    reg p_rst;
    reg [SW*NOUT-1:0] p_osel;
    reg [NP-1:0] p_hi, p_lo;
    reg [NAXES-1:0] p_trip;
    always @(posedge clk) begin
        p_rst <= rst; p_osel <= osel; p_hi <= hi; p_lo <= lo; p_trip <= trip;
    end
    // the register block's guarantee (G4): a select changes only at a reset or with its write pulse
    always @(*) if (f_pv && osel != p_osel) assume(p_rst || osel_wr);

`ifdef ROUTE_R6
    // R6: the phases the current table drives (task map; the scan's invariant is in rtl/out_route.v)
    reg [NP-1:0] f_drv;
    integer fk, fj;
    always @(*) begin
        f_drv = {NP{1'b0}};
        for (fk = 0; fk < NOUT; fk = fk + 1)
            for (fj = 0; fj < NP; fj = fj + 1)
                if (osel[SW*fk +: SW] == fj + 1) f_drv[fj] = 1'b1;
    end
    always @(*) if (f_pv && !osel_wr && !p_rst) assert((mapped & ~f_drv) == 0);                // R6
    reg p_wr;
    reg [NP-1:0] p_mapped;
    always @(posedge clk) begin
        p_wr <= osel_wr;
        p_mapped <= mapped;
    end
    always @(*) if (f_pv && !p_rst && !p_wr) assert((p_mapped & ~mapped) == 0);               // R7
`else
    genvar k, q;
    wire [NP-1:0] p_tp;                                        // previous trip of each pair's axis
    generate
        for (q = 0; q < NP; q = q + 1) begin : g_q
            assign p_tp[q] = p_trip[q / 3];                    // constant index: no divider in the model
        end
        for (k = 0; k < NOUT; k = k + 1) begin : g_k
            wire [SW-1:0] c = p_osel[SW*k +: SW];
            always @(*) if (f_pv) begin
                if (p_rst) assert(!pin_hi[k] && !pin_lo[k]);                                   // R0
                if (c == 0 || c > NP) assert(!pin_hi[k] && !pin_lo[k]);                        // R1
            end
            // one comparison per source pair q (no dynamic index: the base case stays easy for z3)
            for (q = 0; q < NP; q = q + 1) begin : g_src
                always @(*) if (f_pv && !p_rst && c == q + 1) begin
                    if (p_tp[q]) assert(!pin_hi[k] && !pin_lo[k]);                             // R3
                    else assert(pin_hi[k] == p_hi[q] && pin_lo[k] == p_lo[q]);                 // R2
                    if (pin_hi[k] && pin_lo[k]) assert(p_hi[q] && p_lo[q]);                    // R5
                end
            end
        end
    endgenerate
`endif
`ifdef ROUTE_COVER
    always @(*) if (f_pv) begin
        cover(!p_rst && pin_hi[0] && pin_hi[NOUT-1] && p_osel[0 +: SW] == p_osel[SW*(NOUT-1) +: SW]);  // shared
        cover(!p_rst && p_trip[0] && pin_hi[NOUT-1] && p_osel[SW*(NOUT-1) +: SW] == NP);       // other axis on
        cover(mapped == {NP{1'b1}});                                                           // a full scan
    end
`endif
    wire unused = &{1'b0, bad_sel, ax_miso, ax_hall, ax_a, ax_b, ax_i, ax_m};
endmodule
`default_nettype wire
