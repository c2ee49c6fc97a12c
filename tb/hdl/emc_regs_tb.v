// emc_regs_tb: simulation wrapper for emc_bus: the EMC data bus as a resolved
// tristate net shared by the CPU model (tb/emc_bfm.py drives cpu_*) and the
// FPGA, and a register file of NREG read/write registers behind the port.
//
// Register file: word addresses 0..NREG-1 are RW registers (reset 0);
// reads of any other address return 32'hDEAD0000 | addr (AW <= 16; so every
// address bit is observable); writes there are ignored.  reg_rdata is valid
// RD_LAT clocks after reg_rd.  Counters of the port pulses and error pulses
// and a contention flag (both sides driving emc_d) are outputs for the test.
`default_nettype none
module emc_regs_tb #(
    parameter integer AW = 14,
    parameter integer RD_LAT = 1,
    parameter integer WR_MIN_LOW = 3,
    parameter integer RD_MIN_LOW = 2,
    parameter integer OE_PIN_GATE = 1,
    parameter integer NREG = 64
) (
    input  wire          clk,
    input  wire          rst,
    input  wire          cpu_cs_n,
    input  wire          cpu_oe_n,
    input  wire          cpu_we_n,
    input  wire [AW-1:0] cpu_a,
    input  wire [31:0]   cpu_d,
    input  wire          cpu_d_oe,
    output wire          contention,
    output wire          bus_driven,     // some driver on emc_d (2-state simulators read an undriven bus as 0)
    output reg  [31:0]   n_wr,
    output reg  [31:0]   n_rd,
    output reg  [31:0]   n_err_wr,
    output reg  [31:0]   n_err_rd
);
    wire [31:0] emc_d;
    wire [31:0] fpga_d_out;
    wire        fpga_d_oe;
    assign emc_d = cpu_d_oe ? cpu_d : 32'bz;
    assign emc_d = fpga_d_oe ? fpga_d_out : 32'bz;
    assign contention = cpu_d_oe && fpga_d_oe;
    assign bus_driven = cpu_d_oe || fpga_d_oe;

    wire          reg_wr, reg_rd, err_wr_short, err_rd_short;
    wire [AW-1:0] reg_addr;
    wire [31:0]   reg_wdata;
    reg  [31:0]   reg_rdata;

    emc_bus #(.AW(AW), .RD_LAT(RD_LAT), .WR_MIN_LOW(WR_MIN_LOW), .RD_MIN_LOW(RD_MIN_LOW),
              .OE_PIN_GATE(OE_PIN_GATE)) u_bus (
        .clk(clk), .rst(rst), .emc_cs_n(cpu_cs_n), .emc_oe_n(cpu_oe_n), .emc_we_n(cpu_we_n),
        .emc_a(cpu_a), .emc_d_in(emc_d), .emc_d_out(fpga_d_out), .emc_d_oe(fpga_d_oe),
        .reg_wr(reg_wr), .reg_rd(reg_rd), .reg_addr(reg_addr), .reg_wdata(reg_wdata),
        .reg_rdata(reg_rdata), .err_wr_short(err_wr_short), .err_rd_short(err_rd_short));

    reg [31:0] regs [0:NREG-1];
    reg [31:0] rpipe [0:RD_LAT-1];
    localparam integer RI = $clog2(NREG);
    wire [31:0] rd_val = (reg_addr < NREG) ? regs[reg_addr[RI-1:0]] : (32'hDEAD0000 | {{(32-AW){1'b0}}, reg_addr});
    integer i;
    always @(posedge clk) begin
        if (rst) begin
            for (i = 0; i < NREG; i = i + 1) regs[i] <= 32'd0;
            for (i = 0; i < RD_LAT; i = i + 1) rpipe[i] <= 32'd0;
            n_wr <= 0;
            n_rd <= 0;
            n_err_wr <= 0;
            n_err_rd <= 0;
        end else begin
            if (reg_wr && reg_addr < NREG) regs[reg_addr[RI-1:0]] <= reg_wdata;
            rpipe[0] <= reg_rd ? rd_val : 32'hBAD0BAD0;   // only valid RD_LAT clocks after reg_rd
            for (i = 1; i < RD_LAT; i = i + 1) rpipe[i] <= rpipe[i-1];
            n_wr <= n_wr + reg_wr;
            n_rd <= n_rd + reg_rd;
            n_err_wr <= n_err_wr + err_wr_short;
            n_err_rd <= n_err_rd + err_rd_short;
        end
    end
    always @(*) reg_rdata = rpipe[RD_LAT-1];
endmodule
`default_nettype wire
