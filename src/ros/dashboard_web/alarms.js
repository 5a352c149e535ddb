// The alarm log panel (newest first, each alarm once) and the red banner while any item is committed
// or overturned.
import { $, LABELS, SEVERITY, esc, fmt, modeOf, utc, view } from './state.js';

export function addAlarm(a, render = true) {
  // A redundant pair's better copy of an alarm shown (docs/journal.md): it takes the other's place.
  if (a.replaces !== undefined) {
    const old = a.item + '/' + a.level + '/' + a.replaces;
    const i = view.alarms.findIndex((b) => b.item + '/' + b.level + '/' + b.stamp === old);
    if (i >= 0) view.alarms.splice(i, 1);
    view.alarmKeys.delete(old);
  }
  const key = a.item + '/' + a.level + '/' + a.stamp;
  if (view.alarmKeys.has(key)) return;
  view.alarmKeys.add(key);
  view.alarms.unshift(a);  // newest first
  if (render) renderAlarms();
}

export function updateBanner() {
  const bad = view.items.filter((it) => SEVERITY[modeOf(it)] >= SEVERITY.COMMITTED);
  const b = $('banner');
  if (!bad.length) { b.hidden = true; return; }
  bad.sort((a, c) => SEVERITY[modeOf(c)] - SEVERITY[modeOf(a)]);
  const names = bad.slice(0, 8).map((it) => it.id + ' ' + LABELS[modeOf(it)].toUpperCase());
  b.textContent = '\u26a0 ' + bad.length + (bad.length === 1 ? ' item' : ' items') + ' committed or overturned: ' +
                  names.join(', ') + (bad.length > 8 ? ', \u2026' : '');
  b.hidden = false;
}

// An OVERTURNED alarm's cause (OverturnAlarm.cause): "fell_off_support" when the item slid off its
// plinth, shelf or pedestal (docs/dashboard.md); rocking, the usual way, adds nothing.
const CAUSES = { fell_off_support: 'fell off its support' };

export function renderAlarms() {
  const rows = view.alarms.slice(0, 500).map((a) =>
    '<tr data-item="' + esc(a.item) + '" data-level="' + a.level + '"><td>' + utc(a.event_time) + '</td><td>' +
    fmt(a.t, 3) + '</td><td title="' + esc(a.description) + '">' + esc(a.item) + '</td><td data-cause="' +
    esc(a.cause || 'rocking') + '"><span class="mode m-' +
    a.level + '">' + LABELS[a.level] + '</span>' + (CAUSES[a.cause] ? '<br>' + CAUSES[a.cause] : '') + '</td><td>' +
    esc(a.plane) + '</td><td>' + fmt(a.rotation_ratio, 2) +
    '</td><td>' + esc((a.predicted_by || []).join(', ') || 'none') + '</td></tr>');
  $('alarms').tBodies[0].innerHTML = rows.join('') ||
    '<tr><td colspan="7" class="hint">no alarms</td></tr>';
  markAlarmLayout();
}

// Where the alarm log's last column ("predicted by") lies and what of it shows without scrolling, as
// data attributes on the table: the headless browser test (test/ros/dashboard_browser.py) cannot
// measure layout itself, and checks from these that the column is not cut at a 1280-pixel window.
export function markAlarmLayout() {
  const table = $('alarms');
  const col = table.tHead.rows[0].lastElementChild.getBoundingClientRect();
  const scroller = table.parentElement;  // the .scroll box
  const left = scroller.getBoundingClientRect().left + scroller.clientLeft;
  const viewport = document.documentElement.clientWidth;
  table.dataset.viewport = viewport;
  table.dataset.lastColumn = Math.round(col.left) + ',' + Math.round(col.right);
  table.dataset.visible = Math.round(left) + ',' + Math.round(Math.min(left + scroller.clientWidth, viewport));
}
