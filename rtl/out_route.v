// out_route: free assignment of the half-bridge outputs and of the position / current inputs to
// the axes (issue 16 item 4, docs/four_axes.md section 5, docs/blocks/out_route.md).
//
// The select registers are the global routing registers OUT_SEL0/1, ADC_SEL0/1 and IN_SEL of
// gen/empc/regmap.py.  They are stored in the generated rtl/global_regs.v, which refuses (whole
// word, wr_refused, counted in every axis' CNT_WR_REFUSED) a write while any axis is live
// (guard bridges_live: CTRL.enable set or outputs switching, on any axis) and an OUT_SEL code
// beyond the routable pairs.  This block only uses them:
//  - output k (of NOUT): pin_hi[k], pin_lo[k] <= the (axis, phase) pair its OUT_SEL code names
//    (code 0 = off; 1 + 3 a + p = axis a, phase p), registered once after pwm_center; the trip
//    of the owning axis is the register's synchronous reset, so a trip turns the routed pins off
//    at the same edge as pwm_center's own registers.  An output with code 0, or a code naming an
//    axis this build lacks (the reset map names all EMPC_ROUTE_AXES axes), is held off.  The pins then go through out_kill (clock-independent
//    gate), which stays the last stage: no map can route around a kill.
//  - each axis' three current channels (ADC_SEL: one of NADC MISO lines), its IRC input (IN_SEL.enc:
//    one of NENC sets A, B, index, mark) and its HALL set (IN_SEL.hall: one of NHALL) are plain
//    multiplexers.  A select naming an input the build lacks reads the fail-safe value: MISO 1
//    (the ADC frame's leading zero bit fails: FAULT.adc), HALL 000 (illegal: FAULT.hall), IRC 0.
//  - mapped[3 a + p]: phase p of axis a drives at least one output.  A scan of OUT_SEL, one
//    output per clock, NOUT clocks per pass, restarted with mapped = 0 by every accepted OUT_SEL
//    write (osel_wr), so mapped never claims a phase from a table older than the last write but
//    one clock (osel_wr comes with the new value).  The integration makes mapped[a] = 0b111 a
//    condition of axis a's bridges_on (docs/four_axes.md 5.1).
//  - bad_sel: an input select of an axis of this build names a line the build lacks (0 on LX_RoCoN,
//    whose NADC, NENC, NHALL fill the select fields).
// Parameters: NAXES (1..EMPC_ROUTE_AXES) axes; NOUT, NENC, NHALL, NADC: the board's outputs,
// IRC inputs, HALL sets and ADC channels (defaults: LX_RoCoN, empc_regs.vh); the select widths
// SW, AW, EW, HW are those of the register fields.
// Ports: osel = OUT_SEL fields, output k at [SW k +: SW]; asel = ADC_SEL fields of the NAXES axes,
// (a, p) at [AW (3 a + p) +: AW]; esel, hsel = IN_SEL.enc / .hall of the NAXES axes; hi, lo =
// pwm_center's registered outputs, (a, p) at bit 3 a + p; trip = each axis' fault trip.
// Latency: pins 1 clock after hi / lo / trip; input multiplexers combinational (0 clocks);
// mapped NOUT + 1 clocks after the write pulse at the latest (a full scan), bad_sel 1 clock.
// Reset: synchronous (rst): every pin off (also from configuration: INIT 0), mapped 0 (the scan
// restarts), bad_sel 0.
`default_nettype none
`include "empc_regs.vh"
module out_route #(
    parameter integer NAXES = `EMPC_ROUTE_AXES,     // axes of this build (1..EMPC_ROUTE_AXES)
    parameter integer NOUT = `EMPC_ROUTE_OUTPUTS,   // half-bridge outputs
    parameter integer NENC = `EMPC_ROUTE_ENC,       // IRC inputs
    parameter integer NHALL = `EMPC_ROUTE_HALL,     // HALL sets
    parameter integer NADC = `EMPC_ROUTE_ADC,       // current ADC channels (MISO lines)
    parameter integer SW = `EMPC_ROUTE_OUT_W,       // OUT_SEL code bits
    parameter integer AW = `EMPC_ROUTE_ADC_W,       // ADC_SEL channel bits
    parameter integer EW = `EMPC_ROUTE_ENC_W,       // IN_SEL.enc bits
    parameter integer HW = `EMPC_ROUTE_HALL_W       // IN_SEL.hall bits
) (
    input  wire                     clk,
    input  wire                     rst,
    // select registers (global_regs)
    input  wire [SW*NOUT-1:0]       osel,
    input  wire                     osel_wr,        // pulse: an OUT_SEL write was accepted
    input  wire [AW*3*NAXES-1:0]    asel,
    input  wire [EW*NAXES-1:0]      esel,
    input  wire [HW*NAXES-1:0]      hsel,
    // outputs: the axes' pwm_center pairs -> the pins (to out_kill)
    input  wire [3*NAXES-1:0]       hi,
    input  wire [3*NAXES-1:0]       lo,
    input  wire [NAXES-1:0]         trip,
    output reg  [NOUT-1:0]          pin_hi,
    output reg  [NOUT-1:0]          pin_lo,
    // inputs: board lines -> the axes
    input  wire [NADC-1:0]          miso,
    output wire [3*NAXES-1:0]       ax_miso,
    input  wire [NENC-1:0]          irc_a,
    input  wire [NENC-1:0]          irc_b,
    input  wire [NENC-1:0]          irc_idx,
    input  wire [NENC-1:0]          irc_mark,
    output wire [NAXES-1:0]         ax_irc_a,
    output wire [NAXES-1:0]         ax_irc_b,
    output wire [NAXES-1:0]         ax_irc_idx,
    output wire [NAXES-1:0]         ax_irc_mark,
    input  wire [3*NHALL-1:0]       hall,
    output wire [3*NAXES-1:0]       ax_hall,
    // status (ROUTE_STATUS)
    output reg  [3*NAXES-1:0]       mapped,
    output reg                      bad_sel
);
    localparam integer NP = 3 * NAXES;              // routable (axis, phase) pairs
    localparam integer NC = 1 << SW;                // OUT_SEL codes
    localparam integer KW = (NOUT > 1) ? $clog2(NOUT) : 1;
    localparam [31:0] K_LAST_W = NOUT - 1;
    localparam [KW-1:0] K_LAST = K_LAST_W[KW-1:0];

    // ---------------- outputs: code c selects pair c - 1; the owner's trip clears the pair
    wire [NP-1:0] tp;                               // trip of the axis that owns each pair
    genvar j, k, a, p;
    generate
        for (j = 0; j < NP; j = j + 1) begin : g_tp
            assign tp[j] = trip[j / 3];
        end
    endgenerate
    wire [NC-1:0] hv, lv, tv;                       // by code: 0 = off, codes beyond the pairs off
    generate
        if (NC > NP + 1) begin : g_pad
            assign hv = {{(NC - NP - 1){1'b0}}, hi, 1'b0};
            assign lv = {{(NC - NP - 1){1'b0}}, lo, 1'b0};
            assign tv = {{(NC - NP - 1){1'b0}}, tp, 1'b0};
        end else begin : g_nopad
            assign hv = {hi, 1'b0};
            assign lv = {lo, 1'b0};
            assign tv = {tp, 1'b0};
        end
        for (k = 0; k < NOUT; k = k + 1) begin : g_pin
            // hi and lo of one output through the same select and the same register; the owner's
            // trip (one signal per output) is the register's synchronous reset
            wire [SW-1:0] c = osel[SW*k +: SW];
            wire clr = rst || tv[c];
            always @(posedge clk) begin
                if (clr) begin
                    pin_hi[k] <= 1'b0;
                    pin_lo[k] <= 1'b0;
                end else begin
                    pin_hi[k] <= hv[c];
                    pin_lo[k] <= lv[c];
                end
            end
        end
    endgenerate

    // ---------------- inputs: padded to the select range with the fail-safe values
    wire [(1 << AW)-1:0] miso_p;
    wire [(1 << EW)-1:0] ea_p, eb_p, ei_p, em_p;
    wire [3*(1 << HW)-1:0] hall_p;
    generate
        if ((1 << AW) > NADC) begin : g_mpad
            assign miso_p = {{((1 << AW) - NADC){1'b1}}, miso};
        end else begin : g_mfull
            assign miso_p = miso;
        end
        if ((1 << EW) > NENC) begin : g_epad
            assign ea_p = {{((1 << EW) - NENC){1'b0}}, irc_a};
            assign eb_p = {{((1 << EW) - NENC){1'b0}}, irc_b};
            assign ei_p = {{((1 << EW) - NENC){1'b0}}, irc_idx};
            assign em_p = {{((1 << EW) - NENC){1'b0}}, irc_mark};
        end else begin : g_efull
            assign ea_p = irc_a;
            assign eb_p = irc_b;
            assign ei_p = irc_idx;
            assign em_p = irc_mark;
        end
        if ((1 << HW) > NHALL) begin : g_hpad
            assign hall_p = {{(3 * ((1 << HW) - NHALL)){1'b0}}, hall};
        end else begin : g_hfull
            assign hall_p = hall;
        end
        for (a = 0; a < NAXES; a = a + 1) begin : g_ax
            for (p = 0; p < 3; p = p + 1) begin : g_ph
                assign ax_miso[3*a+p] = miso_p[asel[AW*(3*a+p) +: AW]];
                assign ax_hall[3*a+p] = hall_p[3*hsel[HW*a +: HW] + p];
            end
            assign ax_irc_a[a] = ea_p[esel[EW*a +: EW]];
            assign ax_irc_b[a] = eb_p[esel[EW*a +: EW]];
            assign ax_irc_idx[a] = ei_p[esel[EW*a +: EW]];
            assign ax_irc_mark[a] = em_p[esel[EW*a +: EW]];
        end
    endgenerate

    // ---------------- input selects the build cannot serve (ROUTE_STATUS.bad_sel)
    wire [(1 << AW)-1:0] ch_bad;
    wire [(1 << EW)-1:0] enc_bad;
    wire [(1 << HW)-1:0] hall_bad;
    generate
        if ((1 << AW) > NADC) begin : g_chb
            assign ch_bad = {{((1 << AW) - NADC){1'b1}}, {NADC{1'b0}}};
        end else begin : g_chb0
            assign ch_bad = {(1 << AW){1'b0}};
        end
        if ((1 << EW) > NENC) begin : g_eb
            assign enc_bad = {{((1 << EW) - NENC){1'b1}}, {NENC{1'b0}}};
        end else begin : g_eb0
            assign enc_bad = {(1 << EW){1'b0}};
        end
        if ((1 << HW) > NHALL) begin : g_hb
            assign hall_bad = {{((1 << HW) - NHALL){1'b1}}, {NHALL{1'b0}}};
        end else begin : g_hb0
            assign hall_bad = {(1 << HW){1'b0}};
        end
    endgenerate
    reg bad_c;
    integer bi;
    always @(*) begin
        bad_c = 1'b0;
        for (bi = 0; bi < NP; bi = bi + 1) bad_c = bad_c | ch_bad[asel[AW*bi +: AW]];
        for (bi = 0; bi < NAXES; bi = bi + 1)
            bad_c = bad_c | enc_bad[esel[EW*bi +: EW]] | hall_bad[hsel[HW*bi +: HW]];
    end

    // ---------------- mapped: one output per clock, restarted by every OUT_SEL write
    reg  [KW-1:0] scan_k;
    reg  [NP-1:0] acc;
    wire [SW-1:0] cur = osel[SW*scan_k +: SW];
    reg  [NP-1:0] dec;                              // one-hot of the scanned output's pair
    integer di;
    always @(*) begin
        for (di = 0; di < NP; di = di + 1) dec[di] = ({{(32 - SW){1'b0}}, cur} == di + 1);
    end
    always @(posedge clk) begin
        if (rst || osel_wr) begin
            scan_k <= {KW{1'b0}};
            acc <= {NP{1'b0}};
            mapped <= {NP{1'b0}};
        end else if (scan_k == K_LAST) begin
            scan_k <= {KW{1'b0}};
            acc <= {NP{1'b0}};
            mapped <= acc | dec;
        end else begin
            scan_k <= scan_k + 1'b1;
            acc <= acc | dec;
        end
        bad_sel <= !rst && bad_c;
    end
`ifdef FORMAL
    // The scan's inductive invariant for R6, R7 (formal/out_route.sby task map, properties in
    // formal/out_route_props.sv, which assumes what global_regs guarantees: osel changes only at rst
    // or with osel_wr): after a reset clock the scan is at its start; outside a write clock, acc
    // holds exactly the phases of the outputs already scanned (k < scan_k) and mapped is 0 (first
    // pass after a write or reset) or the phases the whole table drives.
    reg f_pv = 1'b0, f_prst = 1'b0;
    always @(posedge clk) begin
        f_pv <= 1'b1;
        f_prst <= rst;
    end
    reg [NP-1:0] f_part, f_all;
    integer fk, fj;
    always @(*) begin
        f_part = {NP{1'b0}};
        f_all = {NP{1'b0}};
        for (fk = 0; fk < NOUT; fk = fk + 1)
            for (fj = 0; fj < NP; fj = fj + 1)
                if (osel[SW*fk +: SW] == fj + 1) begin
                    f_all[fj] = 1'b1;
                    if (fk < scan_k) f_part[fj] = 1'b1;
                end
    end
    always @(*) if (f_pv) begin
        if (f_prst) assert(scan_k == 0 && acc == 0 && mapped == 0);
        if (!f_prst && !osel_wr) assert(acc == f_part && (mapped == 0 || mapped == f_all));
    end
`endif
endmodule
`default_nettype wire
