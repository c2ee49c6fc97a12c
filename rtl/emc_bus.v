// emc_bus: LPC4088 EMC static-memory bus (CS0, 32-bit, active-low CS/OE/WE,
// asynchronous to clk) -> synchronous register port.
//
// Synchronisation: CS, OE and WE pass through sync_2ff; the address and data
// pins pass through their own two register stages (sync_2ff, same depth), so
// every strobe sample is aligned with the address/data sample taken at the
// same clock edge.  Address and data are never used on their own: only the
// samples taken while the (aligned) strobes say the pins are valid.
//
// Write: a write is accepted at the synchronised rising edge of WE, and only
// if the WR_MIN_LOW samples before it all saw WE and CS low.  The address and
// data used are those sampled at the LAST edge that still saw WE low (a hold
// register follows the aligned samples while WE and CS are low), not the
// ones sampled after the rise.  Why this is safe: let WE rise at time Tr.  The
// first edge that samples WE high lies in (Tr - tu, Tr + T + tu], so the last
// edge that sampled it low lies in (Tr - T - tu, Tr + tu] (tu = aperture +
// pin-to-pin skew, ~2.5 ns, T = clock period 10 ns).  The data sample we use
// was taken at that edge, i.e. inside the window where the EMC guarantees
// stable address/data if
//   data/address valid >= T + 2 tu = 15 ns before WE rises (setup), and
//   held >= 2 tu = 5 ns after WE rises (hold; the EMC holds about one EMC
//   clock, >= 8 ns at 120 MHz).
// A bit that changes near a sampling edge can only go metastable in a sample
// outside that window, which is never used; the second stage gives the
// sample used a full clock to resolve.  WR_MIN_LOW consecutive low samples
// need WE low >= WR_MIN_LOW*T + 2 tu: with WR_MIN_LOW = 3, WE low >= 35 ns
// (spec: >= 40 ns); any pulse or noise shorter than 2*T = 20 ns (the
// synchroniser depth) gives at most 2 low samples and can never write.
// Between accesses WE must stay high >= T + 2 tu (spec: >= 20 ns).
// reg_wr rises <= 3*T + tu after WE rises.
//
// Read: a read starts when RD_MIN_LOW consecutive samples see OE and CS low
// with WE high (reads are side-effect free, so the filter only stops noise
// from driving the bus).  reg_rd is issued with the address sampled at that
// edge (address valid at OE fall), reg_rdata is captured RD_LAT clocks later
// into the output register and the data bus is driven (emc_d_oe) until the
// synchronised OE or CS goes high.  OE fall to data at the pin:
//   <= T + tu + (RD_MIN_LOW + 2 + RD_LAT)*T + t_co = 62.5 ns + t_co
// (RD_MIN_LOW = 2, RD_LAT = 1; t_co = output flop + pad ~7 ns), so with the
// CPU's ~5 ns data setup the EMC needs OE low >= 75 ns: spec >= 80 ns (and
// OE high >= 20 ns between reads).  With OE_PIN_GATE = 1 the output enable is
// additionally ANDed with the raw OE and CS pins (no clocked logic sees them),
// so the bus is released within the pad delay after OE/CS rise and a read ->
// write turnaround needs no extra wait; with OE_PIN_GATE = 0 the bus is
// released <= 3*T + tu + t_co (~40 ns) after OE rises (WAITTURN >= 40 ns).
//
// Timing violations (diagnostic pulses, e.g. for a counter):
//   err_wr_short: WE rose after 1..WR_MIN_LOW-1 low samples (write dropped;
//     a write is either done with the right address/data or flagged, never
//     done wrong);
//   err_rd_short: a read strobe ended after fewer than RD_OK =
//     RD_MIN_LOW + RD_LAT + 4 low samples, i.e. less than one clock between
//     the data reaching the pins and the last low sample: always raised for
//     OE low <= (RD_OK-1)*T = 60 ns (the data certainly came too late), never
//     for OE low >= RD_OK*T + 2 tu = 75 ns (inside the 80 ns spec).
// Back-to-back reads with OE high < ~30 ns: the previous read's data may be
// driven at the start of the next read until the synchroniser sees the gap
// (harmless: the CPU does not drive during a read; it samples at the end).
//
// Ports:
//   clk, rst                    clock, synchronous active-high reset
//   emc_cs_n, emc_oe_n, emc_we_n  bus strobes (asynchronous, active low)
//   emc_a[AW-1:0]               word address (asynchronous)
//   emc_d_in[31:0]              data pins, input side (asynchronous)
//   emc_d_out[31:0], emc_d_oe   data pins, output side (the top builds the inout)
//   reg_wr, reg_addr, reg_wdata write pulse, address, data (1 clock); reg_addr and
//                               reg_wdata are valid in the reg_wr / reg_rd clock only (they
//                               are the write's hold registers and follow the pins while WE
//                               and CS are low)
//   reg_rd                      read pulse (1 clock) with reg_addr
//   reg_rdata[31:0]             read data, valid RD_LAT clocks after reg_rd
//   err_wr_short, err_rd_short  timing-violation pulses
// Parameters:
//   AW          address width
//   RD_LAT      register-file read latency in clocks (>= 1)
//   WR_MIN_LOW  WE/CS low samples needed for a write (>= 3 rejects < 20 ns noise)
//   RD_MIN_LOW  OE/CS low samples needed to start a read (>= 1)
//   OE_PIN_GATE 1: emc_d_oe also gated by the raw OE/CS pins (fast release)
// Latency: WE rise -> reg_wr 3 clocks (2 sync + edge); OE fall -> reg_rd
//   RD_MIN_LOW + 2 clocks; reg_rd -> emc_d_oe RD_LAT + 1 clocks.
// Reset: strobes read as high (idle), no access, bus not driven.
// Resources: about 3 + 2*(AW+32) synchroniser flops, AW+32 port and 32 output
//   flops, small counters (189 FF, 17 LUT for AW = 14); no DSP/BRAM.
`default_nettype none
module emc_bus #(
    parameter integer AW = 14,
    parameter integer RD_LAT = 1,
    parameter integer WR_MIN_LOW = 3,
    parameter integer RD_MIN_LOW = 2,
    parameter integer OE_PIN_GATE = 1
) (
    input  wire          clk,
    input  wire          rst,
    input  wire          emc_cs_n,
    input  wire          emc_oe_n,
    input  wire          emc_we_n,
    input  wire [AW-1:0] emc_a,
    input  wire [31:0]   emc_d_in,
    output reg  [31:0]   emc_d_out,
    output wire          emc_d_oe,
    output reg           reg_wr,
    output reg           reg_rd,
    output reg  [AW-1:0] reg_addr,
    output reg  [31:0]   reg_wdata,
    input  wire [31:0]   reg_rdata,
    output reg           err_wr_short,
    output reg           err_rd_short
);
    localparam integer WCW = $clog2(WR_MIN_LOW + 1);
    localparam integer RD_OK = RD_MIN_LOW + RD_LAT + 4;  // low samples of a read in time
    localparam integer RCW = $clog2(RD_OK + 1);
    localparam [WCW-1:0] WMIN = WR_MIN_LOW[WCW-1:0];
    localparam [RCW-1:0] RMIN1 = RD_MIN_LOW[RCW-1:0] - {{(RCW-1){1'b0}}, 1'b1};
    localparam [RCW-1:0] ROK = RD_OK[RCW-1:0];

    // ---------------- synchronisers (aligned: same depth) ----------------
    wire          cs_n_q, oe_n_q, we_n_q;
    wire [AW-1:0] a_q;
    wire [31:0]   d_q;
    sync_2ff #(.WIDTH(3), .RESET_VALUE(3'b111)) u_sync_strobe (
        .clk(clk), .rst(rst), .d({emc_cs_n, emc_oe_n, emc_we_n}), .q({cs_n_q, oe_n_q, we_n_q}));
    sync_2ff #(.WIDTH(AW)) u_sync_addr (.clk(clk), .rst(rst), .d(emc_a), .q(a_q));
    sync_2ff #(.WIDTH(32)) u_sync_data (.clk(clk), .rst(rst), .d(emc_d_in), .q(d_q));

    // ---------------- write ----------------
    reg           we_n_d;
    reg [WCW-1:0] wcnt;           // WE&CS low samples in the current WE low phase
    wire          w_low  = !we_n_q && !cs_n_q;
    wire          we_rise = we_n_q && !we_n_d;

    // ---------------- read ----------------
    reg [RCW-1:0]  rcnt;          // consecutive OE&CS low (WE high) samples, saturating at RD_OK
    reg            rd_act;
    reg [RD_LAT-1:0] rd_pipe;
    reg            drive;
    wire           r_low = !oe_n_q && !cs_n_q && we_n_q && we_n_d;
    wire           rd_fire = r_low && (rcnt == RMIN1);
    integer        pi;

    always @(posedge clk) begin
        reg_wr <= 1'b0;
        reg_rd <= 1'b0;
        err_wr_short <= 1'b0;
        err_rd_short <= 1'b0;
        if (rst) begin
            we_n_d <= 1'b1;
            wcnt <= {WCW{1'b0}};
            reg_addr <= {AW{1'b0}};
            reg_wdata <= 32'd0;
            rcnt <= {RCW{1'b0}};
            rd_act <= 1'b0;
            rd_pipe <= {RD_LAT{1'b0}};
            drive <= 1'b0;
            emc_d_out <= 32'd0;
        end else begin
            // write side
            we_n_d <= we_n_q;
            if (we_n_q)
                wcnt <= {WCW{1'b0}};
            else if (!cs_n_q && wcnt != WMIN)
                wcnt <= wcnt + {{(WCW-1){1'b0}}, 1'b1};
            // reg_addr / reg_wdata are the write's hold registers: they follow the
            // aligned samples while WE and CS are low, so at the WE rise they hold
            // the last sample that still saw WE low (no separate hold register and
            // no address multiplexer; the read address is loaded at rd_fire below)
            if (w_low)
                reg_wdata <= d_q;
            if (w_low || rd_fire)
                reg_addr <= a_q;
            if (we_rise) begin
                if (wcnt == WMIN) begin
                    reg_wr <= 1'b1;
                end else if (wcnt != {WCW{1'b0}}) begin
                    err_wr_short <= 1'b1;
                end
            end
            // read side
            if (!r_low) begin
                if (rcnt != {RCW{1'b0}} && rcnt != ROK)
                    err_rd_short <= 1'b1;
                rcnt <= {RCW{1'b0}};
                rd_act <= 1'b0;
                rd_pipe <= {RD_LAT{1'b0}};
                drive <= 1'b0;
            end else begin
                if (rcnt != ROK)
                    rcnt <= rcnt + {{(RCW-1){1'b0}}, 1'b1};
                if (rd_fire) begin
                    reg_rd <= 1'b1;
                    rd_act <= 1'b1;
                end
                rd_pipe[0] <= reg_rd;
                for (pi = 1; pi < RD_LAT; pi = pi + 1)
                    rd_pipe[pi] <= rd_pipe[pi-1];
                if (rd_act && rd_pipe[RD_LAT-1]) begin
                    emc_d_out <= reg_rdata;
                    drive <= 1'b1;
                end
            end
        end
    end

    generate
        if (OE_PIN_GATE != 0) begin : g_gate
            assign emc_d_oe = drive && !emc_oe_n && !emc_cs_n;
        end else begin : g_nogate
            assign emc_d_oe = drive;
        end
    endgenerate

`ifndef SYNTHESIS
    initial begin
        if (RD_LAT < 1 || WR_MIN_LOW < 1 || RD_MIN_LOW < 1)
            $display("ERROR: emc_bus RD_LAT=%0d WR_MIN_LOW=%0d RD_MIN_LOW=%0d must be >= 1",
                     RD_LAT, WR_MIN_LOW, RD_MIN_LOW);
    end
`endif
endmodule
`default_nettype wire
