// hall_decoder: three HALL sensor inputs -> rotor sector 1..6 for one axis.
//
// hall[2:0] -> sync_2ff -> glitch_filter (DEBOUNCE clocks per bit) -> code,
// then sector = SECTOR_MAP[code] (a parameterised 8 x 3-bit table).  Table
// entries 1..6 are sectors, 0 (or 7) marks an illegal code.
//
// Default mapping (bit0 = HALL A, bit1 = HALL B, bit2 = HALL C; each sensor
// high for 180 deg electrical, A rising at 0 deg, B at 120 deg, C at 240 deg):
// sector s covers the electrical angle [(s-1)*60, s*60) deg measured from the
// HALL reference (pos_sense adds hall_offset):
//   code CBA : 101 001 011 010 110 100   (000, 111 illegal)
//   sector   :  1   2   3   4   5   6
// i.e. SECTOR_MAP = {s(7),s(6),...,s(0)} = {3'd0,3'd5,3'd1,3'd6,3'd3,3'd4,3'd2,3'd0}.
// A motor with other wiring gets its own table (or swap wires): increasing
// sectors must go with increasing electrical angle = counting IRC up.
//
// Outputs (all registered, updated every clock once ready):
//   sector       last legal sector 1..6 (0 until the first legal code); held
//                while the code is illegal
//   valid        1 while the current filtered code is legal
//   change       one-clock pulse when a legal sector differs from the previous
//                legal sector (not for the first sector after reset; a
//                sector -> fault -> same sector sequence gives no pulse)
//   fault_pulse  one-clock pulse on entering an illegal code
//   fault        sticky illegal-code flag; fault_clear clears it unless the code
//                is still illegal (set wins)
//   code         filtered raw code (status)
//   ready        start-up done
// Parameters: DEBOUNCE (clocks a level must be stable, >= 1), SECTOR_MAP,
//   SYNC_STAGES.
// Latency: pin -> code SYNC_STAGES + DEBOUNCE clocks; code -> sector/valid/
//   change/fault 1 clock; total SYNC_STAGES + DEBOUNCE + 1.
// Start-up: as irc_decoder: synchronisers fill, the filter loads the levels,
//   ready after SYNC_STAGES + 2 clocks; then the first legal code sets sector
//   and valid without a change pulse (an illegal first code raises fault).
// Reset: sector 0, valid 0, all flags 0.  Resources: ~3*LEN_W + 15 FFs.
`default_nettype none
module hall_decoder #(
    parameter integer DEBOUNCE = 1000,
    parameter [23:0]  SECTOR_MAP = {3'd0, 3'd5, 3'd1, 3'd6, 3'd3, 3'd4, 3'd2, 3'd0},
    parameter integer SYNC_STAGES = 2
) (
    input  wire       clk,
    input  wire       rst,
    input  wire [2:0] hall,
    input  wire       fault_clear,
    output reg  [2:0] sector,
    output reg        valid,
    output reg        change,
    output reg        fault_pulse,
    output reg        fault,
    output wire [2:0] code,
    output reg        ready
);
    function integer clog2;
        input integer v;
        integer t;
        begin
            clog2 = 0;
            t = v - 1;
            while (t > 0) begin
                clog2 = clog2 + 1;
                t = t >> 1;
            end
        end
    endfunction
    localparam integer LEN_W = (clog2(DEBOUNCE + 1) < 1) ? 1 : clog2(DEBOUNCE + 1);

    wire [2:0] synced;
    sync_2ff #(.WIDTH(3), .STAGES(SYNC_STAGES)) u_sync (
        .clk(clk), .rst(rst), .d(hall), .q(synced)
    );

    // start-up sequencer: a shift register of ones (flip-flops instead of a counter and its
    // compares): init_ge[j] = 1 from the j-th clock after reset on; the filters load in
    // clock SYNC_STAGES, ready rises in clock SYNC_STAGES + 2
    reg  [SYNC_STAGES:0]   init_sh;
    wire [SYNC_STAGES+1:0] init_ge = {init_sh, 1'b1};
    wire filt_load = init_ge[SYNC_STAGES] && !init_ge[SYNC_STAGES+1];

    // the length is always DEBOUNCE: LFSR counters (glitch_filter FIXED, the same q clock for clock)
    glitch_filter #(.WIDTH(3), .FILTER_LEN(DEBOUNCE), .LEN_W(LEN_W), .FIXED((DEBOUNCE < 65536) ? 1 : 0)) u_filt (
        .clk(clk), .rst(rst), .load(filt_load), .len({LEN_W{1'b0}}), .d(synced), .q(code)
    );

    wire [4:0]  map_idx = {1'b0, code, 1'b0} + {2'b00, code};   // 3 * code
    wire [2:0]  s_new   = SECTOR_MAP[map_idx +: 3];
    wire        legal  = (s_new != 3'd0) && (s_new != 3'd7);
    reg         bad;      // previous sample was illegal (for the fault pulse)

    always @(posedge clk) begin
        if (rst) begin
            init_sh     <= {(SYNC_STAGES+1){1'b0}};
            ready       <= 1'b0;
            sector      <= 3'd0;
            valid       <= 1'b0;
            change      <= 1'b0;
            fault_pulse <= 1'b0;
            fault       <= 1'b0;
            bad         <= 1'b0;
        end else if (!ready) begin
            init_sh <= init_ge[SYNC_STAGES:0];
            ready   <= init_sh[SYNC_STAGES];
        end else begin
            valid       <= legal;
            change      <= legal && (sector != 3'd0) && (s_new != sector);
            if (legal) sector <= s_new;
            bad         <= !legal;
            fault_pulse <= !legal && !bad;
            fault       <= !legal | (fault & ~fault_clear);
        end
    end
endmodule
`default_nettype wire
