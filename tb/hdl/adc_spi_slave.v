// adc_spi_slave: simulation-only pin-level model of the three serial ADCs
// read by adc_spi (AD7476 / ADS7886 style, shared SCLK and CS, one MISO each).
//
// Protocol (see rtl/adc_spi.v, docs/blocks/adc_spi.md): CPOL = 1.  At the CS
// falling edge the three input codes are sampled (conversion start) and frame
// bit 0 is driven; frame bit k (k = 1..FRAME_BITS-1) is driven after the k-th
// SCLK falling edge.  Frame, MSB first: LEAD_ZEROS leading bits (0, or the
// `lead` test pattern), ADC_BITS code bits MSB first, trailing zeros.  After
// the FRAME_BITS-th falling edge and while CS is high MISO is 'z'.
//
// Output timing (per launching edge, ps): MISO keeps its old value for
// T_HOLD_PS, is 'x' (invalid) until T_OUT_PS, then holds the new bit.  Set
// T_OUT_PS to the whole round trip you want to model (FPGA clk->pad, isolator,
// t_DO of the ADC, board, input pad).  A master that samples outside the valid
// window reads 'x' (Icarus) and the comparison in the test fails.
// under Verilator (the shared runner builds without --timing) the model is
// zero-delay (MISO changes in the time step of the launching edge) and
// drives 0 instead of 'z' when released.
//
// Ports: sclk, cs_n (from the master), code0..2 (driven by the testbench /
// cocotb; Python writes new codes once per PWM period), lead (3 x LEAD_ZEROS
// leading-bit pattern, 0 for a correct frame), miso[2:0].
// Monitors (read by the test): frames (CS falling edges), s_code0..2 (codes
// sampled at the last CS fall), proto_err (count: CS fall with SCLK low,
// frame with != FRAME_BITS SCLK falling edges, SCLK toggling while CS high),
// cs_high_min_ps / sclk_low_min_ps / sclk_high_min_ps (shortest CS-high and
// SCLK phases seen, ps, after the first frame).
`default_nettype none
`timescale 1ns / 1ps
module adc_spi_slave #(
    parameter integer ADC_BITS   = 12,
    parameter integer FRAME_BITS = 16,
    parameter integer LEAD_ZEROS = 4,
    parameter integer T_HOLD_PS  = 3000,
    parameter integer T_OUT_PS   = 15000
) (
    input  wire                      sclk,
    input  wire                      cs_n,
    input  wire [ADC_BITS-1:0]       code0,
    input  wire [ADC_BITS-1:0]       code1,
    input  wire [ADC_BITS-1:0]       code2,
    input  wire [3*LEAD_ZEROS-1:0]   lead,
    output wire [2:0]                miso
);
    localparam real T_HOLD = T_HOLD_PS / 1000.0;
    localparam real T_OUT  = T_OUT_PS / 1000.0;

`ifdef VERILATOR
    localparam [2:0] RELEASED = 3'b000;     // 2-state: no 'z' (tristate lowering would drop the driver)
`else
    localparam [2:0] RELEASED = 3'bzzz;
`endif
    reg [2:0] miso_r = RELEASED;
    assign miso = miso_r;

    reg [FRAME_BITS-1:0] f0 = 0, f1 = 0, f2 = 0;
    reg [ADC_BITS-1:0] s_code0 = 0, s_code1 = 0, s_code2 = 0;
    integer bitn = 0;
    integer frames = 0;
    integer proto_err = 0;
    integer cs_high_min_ps = 0;
    integer sclk_low_min_ps = 0;
    integer sclk_high_min_ps = 0;
    realtime t_cs_rise = 0.0, t_sclk_fall = 0.0, t_sclk_rise = 0.0;

    function [FRAME_BITS-1:0] mkframe;   // lead | code | TRAIL zeros
        input [ADC_BITS-1:0] c;
        input [LEAD_ZEROS-1:0] l;
        begin
            mkframe = {FRAME_BITS{1'b0}};
            mkframe[FRAME_BITS-1 -: LEAD_ZEROS] = l;
            mkframe[FRAME_BITS-1-LEAD_ZEROS -: ADC_BITS] = c;
        end
    endfunction

    // With VERILATOR defined (no --timing in the shared runner): zero-delay, MISO changes
    // with the launching edge.  Icarus: hold / invalid ('x') / valid timing.
    task launch;
        input [2:0] v;
        begin
`ifdef VERILATOR
            miso_r <= v;
`else
            miso_r <= #(T_HOLD) 3'bxxx;
            miso_r <= #(T_OUT) v;
`endif
        end
    endtask

    task release_out;
        begin
`ifdef VERILATOR
            miso_r <= RELEASED;
`else
            miso_r <= #(T_HOLD) RELEASED;
`endif
        end
    endtask

    function integer tmin;                 // running minimum, 0 = none yet
        input integer old;
        input integer val;
        begin
            tmin = (old == 0 || val < old) ? val : old;
        end
    endfunction

    // One process for all pin events (edge detection by hand), so both
    // simulators order the CS and SCLK actions the same way.
    reg cs_q = 1'bx, sclk_q = 1'bx;        // no edge before the pins are known (2-state: 0)
    always @(cs_n or sclk) begin
        if (cs_q === 1'b1 && cs_n === 1'b0) begin                  // CS falling: convert
            if (sclk !== 1'b1) proto_err = proto_err + 1;
            if (frames > 0) cs_high_min_ps = tmin(cs_high_min_ps, $rtoi(($realtime - t_cs_rise) * 1000.0 + 0.5));
            frames = frames + 1;
            s_code0 = code0; s_code1 = code1; s_code2 = code2;
            f0 = mkframe(code0, lead[0*LEAD_ZEROS +: LEAD_ZEROS]);
            f1 = mkframe(code1, lead[1*LEAD_ZEROS +: LEAD_ZEROS]);
            f2 = mkframe(code2, lead[2*LEAD_ZEROS +: LEAD_ZEROS]);
            bitn = 0;
            launch({f2[FRAME_BITS-1], f1[FRAME_BITS-1], f0[FRAME_BITS-1]});
        end else if (cs_q === 1'b0 && cs_n === 1'b1) begin         // CS rising
            t_cs_rise = $realtime;
            if (frames > 0 && bitn != FRAME_BITS) proto_err = proto_err + 1;
            release_out;
        end
        if (sclk_q === 1'b1 && sclk === 1'b0) begin                // SCLK falling
            if (cs_n === 1'b0) begin
                t_sclk_fall = $realtime;
                if (bitn > 0) sclk_high_min_ps = tmin(sclk_high_min_ps, $rtoi(($realtime - t_sclk_rise) * 1000.0 + 0.5));
                bitn = bitn + 1;
                if (bitn < FRAME_BITS)
                    launch({f2[FRAME_BITS-1-bitn], f1[FRAME_BITS-1-bitn], f0[FRAME_BITS-1-bitn]});
                else
                    release_out;                                    // conversion complete
            end else if (frames > 0) begin
                proto_err = proto_err + 1;                          // SCLK must idle high
            end
        end else if (sclk_q === 1'b0 && sclk === 1'b1 && cs_n === 1'b0) begin   // SCLK rising
            t_sclk_rise = $realtime;
            sclk_low_min_ps = tmin(sclk_low_min_ps, $rtoi(($realtime - t_sclk_fall) * 1000.0 + 0.5));
        end
        cs_q = cs_n;
        sclk_q = sclk;
    end
endmodule
`default_nettype wire
