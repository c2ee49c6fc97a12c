// Generated from gen/empc/regmap.py by gen/empc/regblock.py (python -m empc.regmap --all). Do not edit.
//
// global_regs: global registers of lx_rocon_top (watchdog, time, interrupts).
//
// Write decode, stored registers with their reset values, command pulses, W1C bits and
// the read path of the registers of this block in gen/empc/regmap.py (what each register
// is and the rules: gen/empc/regblock.py, docs/registers.md).  Ports: a stored register
// or field is an output named after it, a read-only value an input of the same name.
// Read path: one shared read register (a case), plus per-register exceptions.
// Parameters: none (build-dependent reset values are empc_formats.vh macros).
// Latency: writes act in the clock after reg_wr (window strobes: combinational);
// reg_rdata is valid the clock after reg_rd and 0 in every other clock.
// Reset: synchronous (rst); stored registers to the map's reset values, pulses and read
// data to 0.
`default_nettype none
module global_regs (
    input  wire        clk,
    input  wire        rst,
    input  wire        reg_wr,                // write strobe (1 clock) for a word of this block
    input  wire        reg_rd,                // read strobe (1 clock)
    input  wire [7:0]  reg_addr,              // word offset in the block
    input  wire [31:0] reg_wdata,
    output wire [31:0] reg_rdata,             // read data, the clock after reg_rd (0 otherwise)
    input  wire [3:0]  caps_naxes,            // CAPS.naxes value
    input  wire [3:0]  caps_horizon,          // CAPS.horizon value
    input  wire [7:0]  caps_img_layout,       // CAPS.img_layout value
    input  wire [7:0]  caps_pwm_per_control,  // CAPS.pwm_per_control value
    input  wire        caps_complementary,    // CAPS.complementary value
    input  wire [31:0] pwm_half,              // PWM_HALF value
    output reg  [31:0] scratch,               // SCRATCH (RW)
    output reg  [10:0] wdog_timeout,          // WDOG_TIMEOUT (RW)
    output reg         wdog_kick,             // WDOG_KICK: pulse when 0x5a5a is written
    input  wire [31:0] time_cnt,              // TIME value
    output reg         irq_status_period,     // IRQ_STATUS.period (W1C)
    input  wire        irq_status_period_set, // set IRQ_STATUS.period
    output reg         irq_status_fault,      // IRQ_STATUS.fault (W1C)
    input  wire        irq_status_fault_set,  // set IRQ_STATUS.fault
    output reg  [1:0]  irq_enable,            // IRQ_ENABLE (RW)
    input  wire        bridges_live,          // guard: writes to its registers are refused while high
    input  wire        wdog_unlock_tick,      // timebase of the WDOG_UNLOCK unlock (pulses)
    output wire [1:0]  wdog_unlock_armed,     // WDOG_UNLOCK unlock: ticks left, 0 = not armed (status, proofs)
    output reg         wr_refused             // pulse: a write was refused (guard, unlock or illegal value)
);

    // ---------------- write decode: one predecode per page, a case on the low bits
    wire wr_p0 = reg_wr && (reg_addr[7:4] == 4'd0);
    // unlock: WDOG_UNLOCK armed with its key until the 2th wdog_unlock_tick; the next write of the block consumes it
    reg  [1:0] unl_cnt;
    wire unl = |unl_cnt;
    assign wdog_unlock_armed = unl_cnt;
    always @(posedge clk) begin
        wdog_kick <= 1'b0;
        wr_refused <= 1'b0;
        if (rst) begin
            scratch <= 32'd0;
            wdog_timeout <= 11'd400;
            irq_status_period <= 1'd0;
            irq_status_fault <= 1'd0;
            irq_enable <= 2'd0;
            unl_cnt <= 2'd0;
        end else begin
            if (irq_status_period_set) irq_status_period <= 1'b1;
            if (irq_status_fault_set) irq_status_fault <= 1'b1;
            if (reg_wr) unl_cnt <= 2'd0;   // consumed by any write
            else if (unl && wdog_unlock_tick) unl_cnt <= unl_cnt - 1'b1;
            if (wr_p0) begin
                case (reg_addr[3:0])
                    4'h4: begin   // SCRATCH
                        scratch <= reg_wdata[31:0];
                    end
                    4'h8: begin   // WDOG_TIMEOUT
                        if (!bridges_live && unl && (reg_wdata[10:0] >= 11'd1)) begin
                            wdog_timeout <= reg_wdata[10:0];
                        end else begin
                            wr_refused <= 1'b1;
                        end
                    end
                    4'h9: begin   // WDOG_KICK
                        wdog_kick <= (reg_wdata[15:0] == 16'd23130);
                    end
                    4'hb: begin   // IRQ_STATUS
                        irq_status_period <= (irq_status_period & ~reg_wdata[0]) | irq_status_period_set;
                        irq_status_fault <= (irq_status_fault & ~reg_wdata[1]) | irq_status_fault_set;
                    end
                    4'hc: begin   // IRQ_ENABLE
                        irq_enable <= reg_wdata[1:0];
                    end
                    4'hd: begin   // WDOG_UNLOCK
                        if (reg_wdata[15:0] == 16'd49374) unl_cnt <= 2'd2;
                        else wr_refused <= 1'b1;
                    end
                    default: ;
                endcase
            end
        end
    end

    // ---------------- read path: gated copies / shared read register, ORed
    wire rd_p0 = reg_rd && (reg_addr[7:4] == 4'd0);
    reg  [31:0]  q_scratch;
    reg  [31:0]  q_mux;
    always @(posedge clk) begin
        q_scratch <= (rd_p0 && reg_addr[3:0] == 4'h4) ? scratch : 32'd0;
        if (rst || !rd_p0) begin
            q_mux <= 32'd0;
        end else begin
            case (reg_addr[3:0])
                4'h0: q_mux <= 32'h454d5043;   // ID
                4'h1: q_mux <= 32'h00010000;   // VERSION
                4'h2: q_mux <= {7'd0, caps_complementary, caps_pwm_per_control, caps_img_layout, caps_horizon, caps_naxes};   // CAPS
                4'h3: q_mux <= pwm_half;   // PWM_HALF
                4'h8: q_mux <= {21'd0, wdog_timeout};   // WDOG_TIMEOUT
                4'ha: q_mux <= time_cnt;   // TIME
                4'hb: q_mux <= {30'd0, irq_status_fault, irq_status_period};   // IRQ_STATUS
                4'hc: q_mux <= {30'd0, irq_enable};   // IRQ_ENABLE
                default: q_mux <= 32'd0;
            endcase
        end
        if (rst) begin
            q_scratch <= 32'd0;
        end
    end
    assign reg_rdata = q_mux
                     | q_scratch;
endmodule
`default_nettype wire
