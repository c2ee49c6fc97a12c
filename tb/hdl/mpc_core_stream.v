// mpc_core_stream: sim-only streaming harness for mpc_core (Verilator, tb/test_mpc_core.py).
//
// On `go` it resets the core, waits for ready (boot image), then executes the binary command
// file IN_FILE, back to back (one command byte, then a big-endian record):
//   'w' addr[2 bytes] data[4 bytes]   cfg write (one per clock)
//   's'                               cfg_swap, then swap_at (a control-period boundary every clock)
//                                     until the bank changed (a refused swap ends the run)
//   'v' n[1 byte], n x {addr[1 byte], data[5 bytes]}
//                                     one update: the n input-buffer words (addr = EMPC_IN_*
//                                     word address, data = 40-bit two's complement) are written
//                                     through in_we, one per clock, then start is pulsed in the
//                                     cycle after the last write
//   'e'                               end: `finished` rises
// For every update one line goes to OUT_FILE: u du u_raw ebar wn flags latency (hex, vectors as
// one number, element 0 in the low bits; latency = start -> done cycles).
// The clock runs here (Verilog delay, Verilator --timing): Python only pulses `go` and waits for
// `finished`, so no Python or GPI callback runs per clock.
`default_nettype none
`timescale 1ns / 1ps
`include "empc_formats.vh"
module mpc_core_stream #(
    parameter integer N = `EMPC_N,
    parameter BOOT_FILE = "coef_boot.hex",
    parameter RSQRT_FILE = "rsqrt.hex",
    parameter IN_FILE = "mpc_stream_in.bin",
    parameter OUT_FILE = "mpc_stream_out.txt",
    parameter integer CLK_HALF_PS = 5000,
    parameter [`EMPC_IMG_CFG_PERIOD_BITS-1:0] PPC_IMG = `EMPC_PWM_PER_CONTROL
) (
    output reg         clk,
    input  wire        go,
    output reg         finished,
    output reg  [63:0] cycles,
    output reg  [31:0] nvec
);
    localparam integer SW = `EMPC_SIG_W;
    localparam integer UW = `EMPC_U_W;
    localparam integer MAXW = `EMPC_IN_WORDS;

    reg rst = 1'b1;
    reg start = 1'b0;
    reg cfg_we = 1'b0, cfg_swap = 1'b0;
    reg [9:0] cfg_addr = 10'd0;
    reg [31:0] cfg_wdata = 32'd0;
    reg in_we = 1'b0;
    reg [5:0] in_addr = 6'd0;
    reg [SW-1:0] in_wdata = {SW{1'b0}};
    wire busy, done, ready, bank, swap_pending, boot_ok, task_pos, img_ok, upl_ok, swap_refused, refused;
    wire [2*UW-1:0] u, du, u_raw;
    wire [3*SW-1:0] ebar;
    wire signed [17:0] wn;
    wire [10:0] flags;
    wire [7:0] latency;

    localparam [2:0] S_IDLE = 3'd0, S_RST = 3'd1, S_BOOT = 3'd2, S_CMD = 3'd3, S_RUN = 3'd4,
                     S_SWAP = 3'd5, S_END = 3'd6, S_WR = 3'd7;
    reg [2:0] state = S_IDLE;
    mpc_core #(.N(N), .BOOT_FILE(BOOT_FILE), .RSQRT_FILE(RSQRT_FILE)) dut (
        .clk(clk), .rst(rst), .start(start), .in_we(in_we), .in_addr(in_addr), .in_wdata(in_wdata),
        .busy(busy), .done(done), .u(u), .du(du),
        .u_raw(u_raw), .ebar(ebar), .wn(wn), .flags(flags), .latency(latency), .fw_thr(32'd0), .fw_hi(), .fw_lo(), .aw(2'b00),
        .cfg_we(cfg_we),
        .cfg_addr(cfg_addr), .cfg_wdata(cfg_wdata), .cfg_swap(cfg_swap), .swap_at(state == S_SWAP && !cfg_swap), .ready(ready),
        .bank(bank), .swap_pending(swap_pending), .boot_ok(boot_ok), .img_ok(img_ok), .upl_ok(upl_ok),
        .swap_refused(swap_refused), .refused(refused), .task_pos(task_pos),
        .pwm_per_control(PPC_IMG)        // the images' control period (the period rule: tb/test_mpc_core.py)
    );

    reg [3:0] rcnt = 4'd0;
    reg bank0 = 1'b0;
    reg [63:0] t_start = 64'd0;
    integer fin = 0, fout = 0, ch, r, k, nw;
    reg [47:0] wrec;
    reg [7:0] nbyte;
    reg [MAXW*48-1:0] vrec;
    reg [7:0] lat;

    initial clk = 1'b0;
    always #(CLK_HALF_PS / 1000.0) clk = ~clk;

    initial begin
        finished = 1'b0;
        cycles = 64'd0;
        nvec = 32'd0;
    end

    // read the next command and act on it (called with the clock edge)
    task next_cmd;
        begin
            cfg_we <= 1'b0;
            ch = $fgetc(fin);
            if (ch == "w") begin
                r = $fread(wrec, fin);
                cfg_we <= 1'b1;
                cfg_addr <= wrec[41:32];
                cfg_wdata <= wrec[31:0];
                state <= S_CMD;
            end else if (ch == "s") begin
                cfg_swap <= 1'b1;
                bank0 <= bank;
                state <= S_SWAP;
            end else if (ch == "v") begin
                r = $fread(nbyte, fin);
                nw = nbyte;
                for (k = 0; k < nw; k = k + 1) begin
                    r = $fread(wrec, fin);
                    vrec[k*48 +: 48] = wrec;
                end
                k = 0;
                state <= S_WR;
            end else begin
                state <= S_END;
            end
        end
    endtask

    always @(posedge clk) begin
        cycles <= cycles + 64'd1;
        start <= 1'b0;
        in_we <= 1'b0;
        cfg_swap <= 1'b0;
        case (state)
            S_IDLE: if (go) begin
                rst <= 1'b1;
                rcnt <= 4'd0;
                fin = $fopen(IN_FILE, "rb");
                fout = $fopen(OUT_FILE, "w");
                if (fin == 0) begin
                    $display("mpc_core_stream: cannot open %s", IN_FILE);
                    state <= S_END;
                end else state <= S_RST;
            end
            S_RST: begin
                rcnt <= rcnt + 4'd1;
                if (rcnt == 4'd3) begin
                    rst <= 1'b0;
                    state <= S_BOOT;
                end
            end
            S_BOOT: if (ready) next_cmd;
            S_CMD: next_cmd;
            S_WR: begin
                cfg_we <= 1'b0;
                if (k < nw) begin
                    in_we <= 1'b1;
                    in_addr <= vrec[k*48+40 +: 6];
                    in_wdata <= vrec[k*48 +: SW];
                    k = k + 1;
                end else begin
                    start <= 1'b1;
                    t_start <= cycles;
                    state <= S_RUN;
                end
            end
            S_RUN: if (done) begin
                lat = cycles - t_start - 64'd1;
                $fwrite(fout, "%h %h %h %h %h %h %h\n", u, du, u_raw, ebar, wn, flags, lat);
                nvec <= nvec + 32'd1;
                next_cmd;
            end
            S_SWAP: if (bank != bank0) next_cmd;
                    else if (refused) begin       // every image of the stream is valid for the build
                        $display("mpc_core_stream: swap refused (image not valid for this build)");
                        state <= S_END;
                    end
            default: if (!finished) begin
                $fclose(fout);
                if (fin != 0) $fclose(fin);
                finished <= 1'b1;
            end
        endcase
    end

    wire unused_ok = &{1'b0, busy, swap_pending, boot_ok, task_pos, latency, r, img_ok, upl_ok, swap_refused};
endmodule
`default_nettype wire
