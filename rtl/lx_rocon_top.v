// lx_rocon_top: LX_RoCoN (XC6SLX9) top level of the explicit-MPC PMSM drive.
//
// STUB: ports are final; the body is filled in by the integration (issue 5).
// Until then every power output is held in the safe state (all bridges off).
`default_nettype none
module lx_rocon_top #(
    parameter integer NAXES = 1,           // motors driven (LX_RoCoN: up to 4 from 16 half-bridges)
    parameter integer EMC_AW = 14          // CPU bus word-address lines
) (
    input  wire                 clk_in,    // board oscillator (CLKIN_HZ), multiplied to the fabric clock
    input  wire                 rst_n_in,  // external reset, active low, asynchronous
    // LPC4088 EMC static memory bus (CS0), asynchronous to the fabric clock
    input  wire                 emc_cs_n,
    input  wire                 emc_oe_n,
    input  wire                 emc_we_n,
    input  wire [EMC_AW-1:0]    emc_a,
    inout  wire [31:0]          emc_d,
    output wire                 cpu_irq,
    // encoders and HALL sensors
    input  wire [NAXES-1:0]     irc_a,
    input  wire [NAXES-1:0]     irc_b,
    input  wire [NAXES-1:0]     irc_idx,
    input  wire [NAXES-1:0]     irc_mark,
    input  wire [3*NAXES-1:0]   hall,
    // LX_PWR half-bridges: PWM (high-side command) + enable per half-bridge
    output wire [3*NAXES-1:0]   pwm_out,
    output wire [3*NAXES-1:0]   pwm_en,
    // current ADCs (3 simultaneous-sampling channels per axis, shared SCLK/CS)
    output wire                 adc_sclk,
    output wire                 adc_cs_n,
    input  wire [3*NAXES-1:0]   adc_miso,
    output wire [1:0]           led
);
    assign emc_d    = 32'bz;
    assign cpu_irq  = 1'b0;
    assign pwm_out  = {3*NAXES{1'b0}};
    assign pwm_en   = {3*NAXES{1'b0}};
    assign adc_sclk = 1'b0;
    assign adc_cs_n = 1'b1;
    assign led      = 2'b00;
    wire unused = &{1'b0, clk_in, rst_n_in, emc_cs_n, emc_oe_n, emc_we_n, emc_a, irc_a, irc_b, irc_idx,
                    irc_mark, hall, adc_miso};
endmodule
`default_nettype wire
