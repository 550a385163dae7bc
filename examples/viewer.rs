//! A model viewer built with ratatui: a list of models beside a spinning 3D
//! view ([`rastty::ratatui::SceneWidget`]) and a status line.
//!
//! ```text
//! cargo run --release --example viewer --features ratatui -- [MODEL ...]
//! ```
//!
//! Without arguments it lists the built-in shapes and the shared models
//! found in `../shared/models`. It starts in the finest glyph mode the
//! terminal draws one cell wide, asked of it with [`rastty::GlyphSupport`]
//! (octants, or sextants in a tmux whose C library lacks them). Keys: arrows orbit, `+`/`-` zoom, Tab and
//! Shift-Tab pick a model, `g` the next glyph mode, space pauses, `q` or
//! Esc quits. Mouse: drag in the view to orbit, right- or Shift-drag to
//! pan (the library's [`rastty::scene::View`], as `rastty spin` moves it),
//! the wheel zooms, a click in the list picks a model.

use rastty::Choice;
use std::io;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use rastty::glam::{Vec2, Vec3};
use rastty::ratatui::{SceneState, SceneWidget};
use rastty::scene::{Shape, View};
use rastty::{GlyphMode, GlyphSupport, RenderOptions, color::ColorDepth, color::Rgb, scene::Scene};
use ratatui::crossterm::cursor::{MoveTo, position};
use ratatui::crossterm::event::{
    self, DisableMouseCapture, EnableMouseCapture, Event, KeyCode, KeyEventKind, KeyModifiers,
    MouseButton, MouseEventKind,
};
use ratatui::crossterm::execute;
use ratatui::crossterm::style::Print;
use ratatui::crossterm::terminal::{Clear, ClearType};
use ratatui::layout::{Constraint, Layout, Position, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::Line;
use ratatui::widgets::{Block, List, ListState, Paragraph};
use ratatui::{DefaultTerminal, Frame};

/// A model the list offers, loaded when first picked.
struct Entry {
    name: String,
    source: Source,
    scene: Option<Result<Scene, String>>,
}

enum Source {
    Shape(Shape),
    File(PathBuf),
}

impl Entry {
    fn scene(&mut self) -> &Result<Scene, String> {
        self.scene.get_or_insert_with(|| match &self.source {
            Source::Shape(s) => Ok(Scene::of_mesh(s.mesh(Rgb::new(0xff, 0x90, 0x40)))),
            Source::File(p) => Scene::of_model(p).map_err(|e| e.to_string()),
        })
    }
}

struct App {
    entries: Vec<Entry>,
    list: ListState,
    options: RenderOptions,
    state: SceneState,
    /// Orbit, zoom and pan of the camera: the library's view, which
    /// `rastty spin`'s mouse moves the same way.
    view: View,
    /// The model's own turn, in degrees, and whether it goes on turning.
    spin: f32,
    /// Seconds played of a moving model's first clip.
    clock: f64,
    paused: bool,
    /// Where a left-button drag was last seen.
    drag: Option<(u16, u16)>,
    /// The areas of the last frame, for the mouse.
    list_area: Rect,
    view_area: Rect,
    fps: f32,
}

fn entries(args: Vec<String>) -> Vec<Entry> {
    let file = |p: PathBuf| Entry {
        name: p
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned(),
        source: Source::File(p),
        scene: None,
    };
    if !args.is_empty() {
        return args.into_iter().map(|a| file(PathBuf::from(a))).collect();
    }
    let mut out: Vec<Entry> = Shape::ALL
        .iter()
        .map(|&s| Entry {
            name: s.name().to_string(),
            source: Source::Shape(s),
            scene: None,
        })
        .collect();
    for name in ["bunny.obj", "teapot.obj", "fox.obj", "linux-mascot-tux.obj"] {
        let p = PathBuf::from("../shared/models").join(name);
        if p.exists() {
            out.push(file(p));
        }
    }
    out
}

fn color_depth() -> ColorDepth {
    match std::env::var("COLORTERM").as_deref() {
        Ok("truecolor" | "24bit") => ColorDepth::TrueColor,
        _ => ColorDepth::Ansi256,
    }
}

impl App {
    fn new(entries: Vec<Entry>) -> App {
        App {
            entries,
            list: ListState::default().with_selected(Some(0)),
            options: RenderOptions {
                // Until the terminal is asked (`best_glyphs`): block
                // elements every terminal and tmux draw one cell wide.
                glyphs: GlyphMode::Quadrant,
                color: color_depth(),
                ..Default::default()
            },
            state: SceneState::new(),
            view: View::AS_GIVEN,
            spin: 0.0,
            clock: 0.0,
            paused: false,
            drag: None,
            list_area: Rect::default(),
            view_area: Rect::default(),
            fps: 0.0,
        }
    }

    fn selected(&self) -> usize {
        self.list.selected().unwrap_or(0)
    }

    fn pick(&mut self, i: usize) {
        if i < self.entries.len() && i != self.selected() {
            self.list.select(Some(i));
            self.view = View::AS_GIVEN;
        }
    }

    fn orbit(&mut self, yaw: f32, pitch: f32) {
        self.view.orbit(yaw, pitch);
    }

    fn zoom(&mut self, factor: f32) {
        self.view.zoom(factor);
    }

    /// Handles one event; `false` to quit.
    fn event(&mut self, event: Event) -> bool {
        match event {
            Event::Key(k) if k.kind != KeyEventKind::Release => match k.code {
                KeyCode::Char('q') | KeyCode::Esc => return false,
                KeyCode::Left => self.orbit(-10.0, 0.0),
                KeyCode::Right => self.orbit(10.0, 0.0),
                KeyCode::Up => self.orbit(0.0, 10.0),
                KeyCode::Down => self.orbit(0.0, -10.0),
                KeyCode::Char('+' | '=') => self.zoom(1.0 / 1.25),
                KeyCode::Char('-') => self.zoom(1.25),
                KeyCode::Tab => self.pick((self.selected() + 1) % self.entries.len()),
                KeyCode::BackTab => {
                    let n = self.entries.len();
                    self.pick((self.selected() + n - 1) % n)
                }
                KeyCode::Char('g') => {
                    let modes = GlyphMode::ALL;
                    let i = modes
                        .iter()
                        .position(|&m| m == self.options.glyphs)
                        .unwrap_or(0);
                    self.options.glyphs = modes[(i + 1) % modes.len()];
                }
                KeyCode::Char(' ') => self.paused = !self.paused,
                _ => {}
            },
            Event::Mouse(m) => {
                let at = Position::new(m.column, m.row);
                match m.kind {
                    MouseEventKind::Down(MouseButton::Left) if self.list_area.contains(at) => {
                        // Inside the list's border, one model a row.
                        let row = m.row.saturating_sub(self.list_area.y + 1) as usize;
                        self.pick(row + self.list.offset());
                    }
                    MouseEventKind::Down(MouseButton::Left | MouseButton::Right)
                        if self.view_area.contains(at) =>
                    {
                        self.drag = Some((m.column, m.row));
                    }
                    MouseEventKind::Drag(button @ (MouseButton::Left | MouseButton::Right)) => {
                        if let Some((x, y)) = self.drag {
                            // As `rastty spin` turns it: a drag across the
                            // view's height is half a turn; the right
                            // button (or Shift) pans.
                            let cells =
                                Vec2::new(m.column as f32 - x as f32, m.row as f32 - y as f32);
                            let pan = button == MouseButton::Right
                                || m.modifiers.contains(KeyModifiers::SHIFT);
                            let rows = self.view_area.height.saturating_sub(2);
                            self.view.drag(cells, rows, self.options.cell_aspect, pan);
                            self.drag = Some((m.column, m.row));
                        }
                    }
                    MouseEventKind::Up(_) => self.drag = None,
                    MouseEventKind::ScrollUp if self.view_area.contains(at) => self.zoom(1.0 / 1.1),
                    MouseEventKind::ScrollDown if self.view_area.contains(at) => self.zoom(1.1),
                    _ => {}
                }
            }
            _ => {}
        }
        true
    }

    fn draw(&mut self, f: &mut Frame) {
        let [main, status] =
            Layout::vertical([Constraint::Fill(1), Constraint::Length(1)]).areas(f.area());
        let [list, view] =
            Layout::horizontal([Constraint::Length(26), Constraint::Fill(1)]).areas(main);
        (self.list_area, self.view_area) = (list, view);

        let names: Vec<&str> = self.entries.iter().map(|e| e.name.as_str()).collect();
        let list_widget = List::new(names)
            .block(Block::bordered().title(" models "))
            .highlight_style(Style::new().add_modifier(Modifier::REVERSED))
            .highlight_symbol("▶ ");
        f.render_stateful_widget(list_widget, list, &mut self.list);

        let block = Block::bordered().title(" view ");
        let inner = block.inner(view);
        f.render_widget(block, view);
        let i = self.selected();
        let (name, view) = (self.entries[i].name.clone(), self.view);
        let text = match self.entries[i].scene() {
            Ok(scene) => {
                let mut scene = scene.clone();
                scene.camera = view.apply(&scene.camera);
                // A model that moves plays its first clip.
                if !scene.clips().is_empty() {
                    scene.set_pose(0, self.clock);
                }
                let options = RenderOptions {
                    turn: Vec3::new(0.0, self.spin, 0.0),
                    ..self.options
                };
                f.render_stateful_widget(
                    SceneWidget::new(&scene, &options),
                    inner,
                    &mut self.state,
                );
                let stats = self.state.renderer().stats();
                format!(
                    " {name}: {} triangles · {} glyphs · {} · {:.0} fps · yaw {:.0}° pitch {:.0}° zoom {:.2}{} · arrows/drag orbit, wheel zoom, Tab model, g glyphs, q quits",
                    stats.triangles_in,
                    self.options.glyphs.name(),
                    self.options.color.name(),
                    self.fps,
                    view.yaw,
                    view.pitch,
                    1.0 / view.distance,
                    if self.paused { " · paused" } else { "" },
                )
            }
            Err(e) => {
                f.render_widget(
                    Paragraph::new(e.as_str()).style(Style::new().fg(Color::Red)),
                    inner,
                );
                format!(" {name}: could not be loaded")
            }
        };
        f.render_widget(
            Line::from(text).style(Style::new().add_modifier(Modifier::REVERSED)),
            status,
        );
    }
}

fn run(terminal: &mut DefaultTerminal, mut app: App) -> io::Result<()> {
    const FRAME: Duration = Duration::from_millis(33);
    let mut last = Instant::now();
    loop {
        let start = Instant::now();
        terminal.draw(|f| app.draw(f))?;
        // Every waiting event is handled before the next frame.
        let deadline = start + FRAME;
        while event::poll(deadline.saturating_duration_since(Instant::now()))? {
            if !app.event(event::read()?) {
                return Ok(());
            }
        }
        let now = Instant::now();
        let dt = (now - last).as_secs_f32();
        last = now;
        app.fps = 0.9 * app.fps + 0.1 / dt.max(1e-3);
        if !app.paused {
            app.spin = (app.spin + 40.0 * dt) % 360.0;
            app.clock += f64::from(dt);
        }
    }
}

/// The best glyph mode this terminal draws one cell wide, asked of it: each
/// probe glyph written at the top-left corner and the cursor's column read
/// back (crossterm's `cursor::position`, which waits up to two seconds for a
/// terminal that does not answer; the asking stops at the first silence).
/// Octants where it can, as tmux with an old C library cannot.
fn best_glyphs() -> io::Result<GlyphMode> {
    let mut out = io::stdout();
    let support = GlyphSupport::ask(|c| -> io::Result<Option<u16>> {
        execute!(out, MoveTo(0, 0), Print(c))?;
        Ok(position().ok().map(|(col, _)| col))
    })?;
    execute!(out, MoveTo(0, 0), Clear(ClearType::CurrentLine))?;
    Ok(support.best(GlyphMode::Octant))
}

fn main() -> io::Result<()> {
    let mut app = App::new(entries(std::env::args().skip(1).collect()));
    let mut terminal = ratatui::init();
    app.options.glyphs = best_glyphs()?;
    terminal.clear()?;
    execute!(io::stdout(), EnableMouseCapture)?;
    let result = run(&mut terminal, app);
    execute!(io::stdout(), DisableMouseCapture)?;
    ratatui::restore();
    result
}
